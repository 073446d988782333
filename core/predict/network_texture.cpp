#include "core/predict/network_texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/data/record_layout.h"
#include "core/nn/derived_inputs.h"
#include "core/nn/encoding.h"
#include "core/nn/encodings/frequency.h"
#include "core/nn/encodings/hash_grid.h"
#include "core/nn/encodings/one_blob.h"
#include "core/nn/encodings/registry.h"

namespace rrf {

namespace {

int vec4s(int n) { return (n + 3) / 4; }

/// Raw input slots of the shader (rawIn[6]): 12 geometric, up to 8 BRDF parameters, 3 derived
/// (nn/derived_inputs.h) and one of padding.
constexpr int kRawSlots = 24;

// Texel offsets and counts are stored as floats; integers up to 2^24 are exact in float.
constexpr size_t kMaxExactInteger = size_t(1) << 24;

/// Appends texels to a growing float array (4 floats each).
class TexelWriter {
public:
    size_t texel() const { return data_.size() / 4; }
    void texel4(float a, float b, float c, float d) { data_.insert(data_.end(), {a, b, c, d}); }
    /// Writes `n` values as ⌈n/4⌉ texels, zero-padded.
    template <typename Get> void padded(int n, Get get) {
        for (int i = 0; i < 4 * vec4s(n); ++i) data_.push_back(i < n ? float(get(i)) : 0.f);
    }
    std::vector<float>& data() { return data_; }

private:
    std::vector<float> data_;
};

int slotOf(const std::string& target) {
    if (target == "direct") return kSlotDirect;
    if (target == "indirect") return kSlotIndirect;
    if (target == "global") return kSlotGlobal;
    if (target == "joint") return kSlotJoint;
    throw std::invalid_argument("unknown network target '" + target + "'");
}

// Encoding component types as the texture stores them (shaders/encoding.glsl).
constexpr int kFrequency = FrequencyEncoding::kGlslId;
constexpr int kOneBlob = OneBlobEncoding::kGlslId;

/// The component type id the texture stores (shaders/encoding.glsl), from the encoding registry.
int glslEncodingId(const Encoding& e) {
    const EncodingType* t = findEncodingType(e.typeName());
    if (!t) throw std::invalid_argument(std::string("network texture: the GLSL predictor has no encoding '") + e.typeName() + "'");
    return t->glslId;
}

/// Hash-grid settings as the texture stores them, from the component's HashGridEncoding.
struct HashGridLayout {
    int levels = 0, log2Size = 0, perLevel = 0;
    std::vector<int> resolution;  ///< per level
    std::vector<bool> dense;      ///< per level: (res + 1)^d ≤ 2^log2Size
    size_t tableFloats() const { return size_t(levels) * (size_t(1) << log2Size) * size_t(perLevel); }
};

HashGridLayout hashGridLayout(const EncodingComponent& c) {
    const auto* grid = dynamic_cast<const HashGridEncoding*>(c.encoding.get());
    if (!grid) throw std::invalid_argument("network texture: a hash_grid component that is not a HashGridEncoding");
    const HashGridSettings& s = grid->settings();
    HashGridLayout g;
    g.levels = s.levels;
    g.log2Size = s.log2TableSize;
    g.perLevel = s.featuresPerLevel;
    for (int l = 0; l < g.levels; ++l) {  // the encoding's own resolutions and dense/hashed choice
        g.resolution.push_back(grid->levelResolution(l));
        g.dense.push_back(grid->levelIsDense(l));
    }
    return g;
}

/// Writes the encoding section of a network block (layout in network_texture.h) and returns, per
/// hash-grid component, the texel whose w holds its table's offset (patched when the table is written).
std::vector<std::pair<size_t, const EncodingComponent*>> writeEncoding(TexelWriter& w, const InputEncoding& e,
                                                                         int scaledInputs) {
    std::vector<std::pair<size_t, const EncodingComponent*>> tables;
    int first = 0;
    for (const EncodingComponent& c : e.components) {
        const int d = int(c.inputs.size()), outs = c.encoding->outputDims();
        const int type = glslEncodingId(*c.encoding);
        w.texel4(float(type), float(d), float(first), float(outs));
        w.padded(d, [&](int i) { return float(c.inputs[size_t(i)]); });
        if (type == kFrequency) {
            const FrequencySettings& s = dynamic_cast<const FrequencyEncoding&>(*c.encoding).settings();
            w.texel4(float(s.frequencies), s.includeInput ? 1.f : 0.f, 0.f, 0.f);
        } else if (type == kOneBlob) {
            w.texel4(float(dynamic_cast<const OneBlobEncoding&>(*c.encoding).settings().bins), 0.f, 0.f, 0.f);
        } else {
            const HashGridLayout g = hashGridLayout(c);
            tables.emplace_back(w.texel(), &c);
            w.texel4(float(g.levels), float(g.log2Size), float(g.perLevel), -1.f);
            w.padded(2 * g.levels, [&](int i) { return i % 2 ? (g.dense[size_t(i / 2)] ? 1.f : 0.f) : float(g.resolution[size_t(i / 2)]); });
        }
        first += outs;
    }
    std::vector<int> pass;  // the identity passes every input through
    if (e.isIdentity())
        for (int i = 0; i < scaledInputs; ++i) pass.push_back(i);
    else
        pass = e.passThrough();
    w.padded(int(pass.size()), [&](int i) { return float(pass[size_t(i)]); });
    return tables;
}

void writeNetwork(TexelWriter& w, const NetworkModel& m) {
    const MlpArch& a = m.arch;
    const InputEncoding& enc = m.encoding;
    // The scaler covers the raw inputs and the derived ones after them (nn/derived_inputs.h).
    const int scaledInputs = m.scaledInputs();
    const int passCount = enc.isIdentity() ? scaledInputs : int(enc.passThrough().size());
    w.texel4(float(scaledInputs), float(a.outputs), float(a.numLayers()), a.activation == Activation::Relu ? 1.f : 0.f);
    w.texel4(float(enc.components.size()), float(a.inputs), float(passCount), enc.derived.reflected ? 1.f : 0.f);
    // The shader computes in float what NetworkModel::predict computes in float: the same casts of
    // the double-precision scalers, encoding parameters and weights.
    w.padded(scaledInputs, [&](int i) { return float(m.inputScaler.offset[i]); });
    w.padded(scaledInputs, [&](int i) { return float(m.inputScaler.scale[i]); });
    w.padded(a.outputs, [&](int i) { return float(m.outputScaler.offset[i]); });
    w.padded(a.outputs, [&](int i) { return float(m.outputScaler.scale[i]); });
    const auto tables = writeEncoding(w, enc, scaledInputs);
    for (int l = 0; l < a.numLayers(); ++l) {
        const int in = a.layerInputs(l), out = a.layerOutputs(l);
        w.texel4(float(in), float(out), float(vec4s(in)), 0.f);
        const double* W = m.params.data() + a.weightOffset(l);  // out × in, column-major
        for (int j = 0; j < out; ++j) w.padded(in, [&](int i) { return float(W[size_t(j) + size_t(i) * size_t(out)]); });
        const double* b = m.params.data() + a.biasOffset(l);
        w.padded(out, [&](int j) { return float(b[j]); });
    }
    const VecX<double>& params = m.encodingParams;
    for (const auto& table : tables) {
        // Not a structured binding: C++17 lambdas cannot capture one (clang refuses).
        const auto descriptor = table.first;
        const auto* c = table.second;
        w.data()[4 * descriptor + 3] = float(w.texel());
        const size_t n = hashGridLayout(*c).tableFloats();
        const Eigen::Index offset = Eigen::Index(c->paramOffset);
        w.padded(int(n), [&](int i) { return params[offset + i]; });
    }
}

// ---- reference evaluation (mirrors shaders/predict.frag) -------------------------------------------

struct TexelReader {
    const NetworkTexture& t;
    const float* texel(int i) const {
        if (i < 0 || size_t(i) >= t.texelCount()) throw std::out_of_range("network texture: texel index out of range");
        return &t.texels[4 * size_t(i)];
    }
    float at(int i, int c) const { return texel(i)[c]; }
};

/// Eigen 3.4's float tanh (generic_fast_tanh_float), as shaders/predict.frag evaluates it.
float tanhEigen(float a) {
    const float x = std::clamp(a, -7.90531110763549805f, 7.90531110763549805f), x2 = x * x;
    float p = x2 * -2.76076847742355e-16f + 2.00018790482477e-13f;
    p = x2 * p + -8.60467152213735e-11f;
    p = x2 * p + 5.12229709037114e-08f;
    p = x2 * p + 1.48572235717979e-05f;
    p = x2 * p + 6.37261928875436e-04f;
    p = x2 * p + 4.89352455891786e-03f;
    p = x * p;
    float q = x2 * 1.19825839466702e-06f + 1.18534705686654e-04f;
    q = x2 * q + 2.26843463243900e-03f;
    q = x2 * q + 4.89352518554385e-03f;
    return std::fabs(a) < 0.0004f ? a : p / q;
}

float dot4(const float* a, const float* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]; }

constexpr float kPiFloat = 3.14159265358979323846f;  // float(π · 2^k) = kPiFloat · 2^k exactly
constexpr uint32_t kHashPrimes[4] = {1u, 2654435761u, 805459861u, 3674653429u};

/// Same steps as rrfEncode() in shaders/encoding.glsl: writes the features of the encoding whose
/// component descriptors start at texel t into `act` (zeroed, features ≤ its size) from the scaled
/// inputs `x`; returns the texel after the pass-through indices.
int encodeFeatures(const TexelReader& r, int t, int comps, int features, int passCount, const float* x, float* act) {
    auto input = [&](int at, int i) { return x[int(r.at(at + i / 4, i % 4))]; };
    for (int c = 0; c < comps; ++c) {
        const int type = int(r.at(t, 0)), d = int(r.at(t, 1)), first = int(r.at(t, 2));
        const int inputsAt = t + 1, settingsAt = inputsAt + vec4s(d);
        const float* set = r.texel(settingsAt);
        t = settingsAt + 1;
        int j = first;
        if (type == kFrequency) {
            const int frequencies = int(set[0]);
            const bool includeInput = set[1] > 0.5f;
            for (int i = 0; i < d; ++i) {
                const float xi = input(inputsAt, i);
                if (includeInput) act[j++] = xi;
                float m = kPiFloat;
                for (int k = 0; k < frequencies; ++k) {
                    const float a = xi * m;
                    act[j++] = std::sin(a);
                    act[j++] = std::cos(a);
                    m *= 2.f;
                }
            }
        } else if (type == kOneBlob) {
            const int bins = int(set[0]);
            const float b = float(bins);
            for (int i = 0; i < d; ++i) {
                const float u = std::clamp((input(inputsAt, i) + 1.f) * 0.5f, 0.f, 1.f);
                for (int k = 0; k < bins; ++k) {
                    const float z = (u - (float(k) + 0.5f) / b) * b;
                    act[j++] = std::exp(-0.5f * z * z);
                }
            }
        } else {
            const int levels = int(set[0]), log2Size = int(set[1]), perLevel = int(set[2]), table = int(set[3]);
            const uint32_t mask = (uint32_t(1) << log2Size) - 1u;
            float u[4];
            for (int i = 0; i < d; ++i) u[i] = std::clamp((input(inputsAt, i) + 1.f) * 0.5f, 0.f, 1.f);
            for (int l = 0; l < levels; ++l) {
                const int res = int(r.at(t + l / 2, (l % 2) * 2));
                const bool dense = r.at(t + l / 2, (l % 2) * 2 + 1) > 0.5f;
                const float s = float(res);
                int cell[4];
                float f[4];
                for (int i = 0; i < d; ++i) {
                    const float pos = u[i] * s;
                    cell[i] = std::min(int(std::floor(pos)), res - 1);
                    f[i] = pos - float(cell[i]);
                }
                float* out = act + first + l * perLevel;
                std::fill(out, out + perLevel, 0.f);
                for (int k = 0; k < (1 << d); ++k) {
                    float w = 1.f;
                    uint32_t idx = 0, stride = 1;
                    for (int i = 0; i < d; ++i) {
                        const bool up = ((k >> i) & 1) != 0;
                        w *= up ? f[i] : 1.f - f[i];
                        const uint32_t v = uint32_t(cell[i] + (up ? 1 : 0));
                        if (dense) {
                            idx += v * stride;
                            stride *= uint32_t(res + 1);
                        } else {
                            idx ^= v * kHashPrimes[i];
                        }
                    }
                    if (!dense) idx &= mask;
                    const int at = ((l << log2Size) + int(idx)) * perLevel;
                    for (int q = 0; q < perLevel; ++q) out[q] += w * r.at(table + (at + q) / 4, (at + q) % 4);
                }
            }
            t += (levels + 1) / 2;
        }
    }
    for (int q = 0; q < passCount; ++q) act[features - passCount + q] = x[int(r.at(t + q / 4, q % 4))];
    return t + vec4s(passCount);
}

/// Same steps as predictNetwork() in shaders/predict.frag; `out` receives up to 8 outputs.
void evaluateNetwork(const TexelReader& r, int base, const float* raw, float* out) {
    const int in = int(r.at(base, 0)), outs = int(r.at(base, 1)), layers = int(r.at(base, 2));
    const bool relu = r.at(base, 3) > 0.5f;
    const int comps = int(r.at(base + 1, 0)), features = int(r.at(base + 1, 1)), passCount = int(r.at(base + 1, 2));
    const int inV = vec4s(in), outV = vec4s(outs);
    int t = base + 2;
    const int inOff = t, inScale = t + inV, outOff = t + 2 * inV, outScale = t + 2 * inV + outV;
    t += 2 * inV + 2 * outV;
    std::vector<float> a(size_t(4 * vec4s(std::max({r.t.maxLayerWidth, in, features}))), 0.f), b(a.size(), 0.f);
    float x[kRawSlots] = {};
    for (int i = 0; i < in; ++i) x[i] = (raw[i] - r.at(inOff + i / 4, i % 4)) * r.at(inScale + i / 4, i % 4);
    if (comps == 0) {  // identity: the features are x' (the pass-through indices are 0 … in−1)
        std::copy(x, x + in, a.begin());
        t += vec4s(passCount);
    } else {
        t = encodeFeatures(r, t, comps, features, passCount, x, a.data());
    }
    for (int l = 0; l < layers; ++l) {
        const int nOut = int(r.at(t, 1)), R = int(r.at(t, 2));
        const int rows = t + 1, bias = rows + nOut * R;
        std::fill(b.begin(), b.end(), 0.f);
        for (int j = 0; j < nOut; ++j) {
            float s = r.at(bias + j / 4, j % 4);
            for (int k = 0; k < R; ++k) s += dot4(r.texel(rows + j * R + k), &a[size_t(4 * k)]);
            if (l + 1 < layers) s = relu ? std::max(s, 0.f) : tanhEigen(s);
            b[size_t(j)] = s;
        }
        std::swap(a, b);
        t = bias + vec4s(nOut);
    }
    for (int k = 0; k < outs; ++k) out[k] = a[size_t(k)] / r.at(outScale + k / 4, k % 4) + r.at(outOff + k / 4, k % 4);
}

/// Same steps as findLeafNetwork() in shaders/predict.frag: walks the tree block at `tree` with the
/// raw inputs and returns the texel offset of the leaf's network block.
int findLeafNetwork(const TexelReader& r, int tree, const float* raw) {
    const int count = int(r.at(tree, 0));
    int node = 0;
    for (int step = 0; step < count; ++step) {
        const float* n = r.texel(tree + 1 + node);
        if (n[0] < 0.f) return int(n[1]);
        node = raw[int(n[0])] < n[1] ? int(n[2]) : int(n[3]);
    }
    throw std::out_of_range("network texture: tree walk did not reach a leaf");
}

}  // namespace

NetworkTexture packNetworkTexture(const Scene& scene, const ModelSet& models, int maxLayerWidth, int maxRows) {
    const RecordLayout layout = RecordLayout::forScene(scene);
    NetworkTexture tex;
    tex.objectCount = int(scene.objects.size());
    tex.inputCount = layout.inputCount();
    tex.offsets.assign(scene.objects.size(), {-1, -1, -1, -1});
    if (tex.inputCount - 12 > 8) throw std::invalid_argument("network texture: more than 8 BRDF parameters");
    if (tex.inputCount + 3 > kRawSlots) throw std::invalid_argument("network texture: no room for the derived inputs");

    // Validate everything before writing, so that a bad model set fails with one clear message.
    int widest = tex.inputCount;
    for (const ObjectNetworks& on : models.objects) {
        if (on.objectId < 0 || on.objectId >= tex.objectCount)
            throw std::invalid_argument("network texture: object id " + std::to_string(on.objectId) +
                                        " is not an object of the scene (" + std::to_string(tex.objectCount) +
                                        " objects)");
        for (const auto& [target, m] : on.byTarget) {
            const int slot = slotOf(target);
            const std::string who = "network '" + target + "' of object " + std::to_string(on.objectId);
            m.validate();
            const MlpArch& arch = m.arch();
            if (m.rawInputs() != tex.inputCount)
                throw std::invalid_argument(who + " has " + std::to_string(m.rawInputs()) + " inputs, the scene's records " +
                                            std::to_string(tex.inputCount));
            // validate() checked that every leaf's encoding writes the features its first layer reads.
            widest = std::max(widest, arch.inputs);
            for (const NetworkModel& leaf : m.leaves)
                for (const EncodingComponent& c : leaf.encoding.components) {
                    glslEncodingId(*c.encoding);  // one the shader knows
                    if (!dynamic_cast<const HashGridEncoding*>(c.encoding.get())) continue;
                    if (c.inputs.empty() || c.inputs.size() > 4)
                        throw std::invalid_argument(who + ": the GLSL hash grid reads 1 to 4 inputs, not " +
                                                    std::to_string(c.inputs.size()));
                    tex.tableTexels += size_t(vec4s(int(std::min(hashGridLayout(c).tableFloats(), kMaxExactInteger * 4))));
                }
            const int wantOut = slot == kSlotJoint ? 6 : 3;
            if (arch.outputs != wantOut)
                throw std::invalid_argument(who + " has " + std::to_string(arch.outputs) + " outputs, expected " +
                                            std::to_string(wantOut));
            for (int l = 0; l < arch.numLayers(); ++l) widest = std::max(widest, arch.layerOutputs(l));
            // The shader indexes its 20 raw inputs (5 vec4s) with the split axis.
            for (const PartitionNode& n : m.tree.nodes)
                if (!n.isLeaf() && n.axis >= 12)
                    throw std::invalid_argument(who + " splits on input " + std::to_string(n.axis) +
                                                ", the GLSL predictor looks leaves up on the 12 geometric inputs only");
            tex.maxTreeDepth = std::max(tex.maxTreeDepth, m.tree.depth());
        }
    }
    if (widest > maxLayerWidth)
        throw std::invalid_argument("network texture: a layer (or encoding) of " + std::to_string(widest) +
                                    " neurons (features) is wider than the GLSL predictor's limit of " +
                                    std::to_string(maxLayerWidth));
    if (tex.tableTexels / size_t(tex.width) > size_t(maxRows))  // before allocating them
        throw std::invalid_argument("network texture: the hash-grid tables alone take " + std::to_string(tex.tableTexels) +
                                    " texels, more than the limit of " + std::to_string(maxRows) + " rows of " +
                                    std::to_string(tex.width) + "; use fewer levels or a smaller log2_table_size");
    if (tex.tableTexels >= kMaxExactInteger)
        throw std::invalid_argument("network texture: the hash-grid tables take " + std::to_string(tex.tableTexels) +
                                    " texels, more than float texel indices address (2^24); use fewer levels "
                                    "or a smaller log2_table_size");
    tex.maxLayerWidth = widest;

    TexelWriter w;
    w.texel4(float(kNetworkTextureVersion), float(tex.objectCount), float(tex.inputCount), float(widest));
    // Object table first (offsets patched below), then the network blocks.
    for (const Object& o : scene.objects) {
        w.texel4(-1.f, -1.f, -1.f, -1.f);
        float brdf[8] = {0, 0, 0, 0, 0, 0, 0, 0};
        layout.brdfParameters(scene.materials.at(size_t(o.material)), brdf);
        w.texel4(brdf[0], brdf[1], brdf[2], brdf[3]);
        w.texel4(brdf[4], brdf[5], brdf[6], brdf[7]);
    }
    for (const ObjectNetworks& on : models.objects) {
        for (const auto& [target, m] : on.byTarget) {
            const size_t at = w.texel();
            tex.offsets[size_t(on.objectId)][size_t(slotOf(target))] = int(at);
            w.data()[4 * (1 + 3 * size_t(on.objectId)) + size_t(slotOf(target))] = float(at);
            // Tree block (node texels patched with the leaves' network offsets), then the leaves' networks.
            const size_t nodes = m.tree.nodes.size();
            w.texel4(float(nodes), float(m.leafCount()), 0.f, 0.f);
            for (const PartitionNode& n : m.tree.nodes) {
                if (n.isLeaf()) w.texel4(-1.f, 0.f, 0.f, 0.f);
                else w.texel4(float(n.axis), n.split, float(n.left), float(n.right));
            }
            for (int l = 0; l < m.leafCount(); ++l) {
                const size_t net = w.texel();
                if (net >= kMaxExactInteger) throw std::invalid_argument("network texture: too many weights for float offsets");
                for (size_t k = 0; k < nodes; ++k)
                    if (m.tree.nodes[k].isLeaf() && m.tree.nodes[k].leaf == l) w.data()[4 * (at + 1 + k) + 1] = float(net);
                writeNetwork(w, m.leaves[size_t(l)]);
                ++tex.networkCount;
            }
        }
    }
    tex.provides.assign(tex.offsets.size(), {false, false, false});
    bool anyNetworks = false;
    for (int t = 0; t < 3; ++t) tex.termAvailable[t] = true;
    for (size_t o = 0; o < tex.offsets.size(); ++o) {
        const auto& off = tex.offsets[o];
        if (off[0] < 0 && off[1] < 0 && off[2] < 0 && off[3] < 0) continue;
        anyNetworks = true;
        const bool d = off[kSlotDirect] >= 0 || off[kSlotJoint] >= 0, i = off[kSlotIndirect] >= 0 || off[kSlotJoint] >= 0;
        tex.provides[o] = {d, i, (d && i) || off[kSlotGlobal] >= 0};
        for (int t = 0; t < 3; ++t) tex.termAvailable[t] = tex.termAvailable[t] && tex.provides[o][size_t(t)];
    }
    if (!anyNetworks)
        for (int t = 0; t < 3; ++t) tex.termAvailable[t] = false;

    const size_t texels = w.texel();
    const size_t rows = (texels + size_t(tex.width) - 1) / size_t(tex.width);
    if (rows > size_t(maxRows))
        throw std::invalid_argument("network texture: " + std::to_string(texels) + " texels need " + std::to_string(rows) +
                                    " rows of " + std::to_string(tex.width) + ", more than the limit of " +
                                    std::to_string(maxRows) +
                                    (tex.tableTexels > 0 ? " (hash-grid tables: " + std::to_string(tex.tableTexels) +
                                                               " texels; use fewer levels or a smaller log2_table_size)"
                                                         : std::string()));
    if (texels > kMaxExactInteger)
        throw std::invalid_argument("network texture: " + std::to_string(texels) +
                                    " texels, more than float texel indices address (2^24)");
    tex.height = int(rows);
    tex.texels = std::move(w.data());
    tex.texels.resize(4 * tex.texelCount(), 0.f);
    return tex;
}

std::array<Vec3, 3> evaluateTerms(const NetworkTexture& tex, int objectId, const float geometricInputs[12]) {
    std::array<Vec3, 3> terms{Vec3(0.f), Vec3(0.f), Vec3(0.f)};
    if (objectId < 0 || objectId >= tex.objectCount) return terms;
    const TexelReader r{tex};
    float raw[kRawSlots] = {};
    std::copy(geometricInputs, geometricInputs + 12, raw);
    const float* brdf = r.texel(2 + 3 * objectId);
    for (int i = 12; i < tex.inputCount; ++i) raw[i] = brdf[i - 12];  // texels 2+3o and 3+3o are adjacent
    // The derived reflected direction follows the record inputs; a network without it reads the
    // slots through zero scales (the scaler's padding), so every network can share one array.
    reflectAboutNormal(raw + kViewInput, raw + kNormalInput, raw + tex.inputCount);
    const float* off = r.texel(1 + 3 * objectId);
    float y[8];
    // Non-finite outputs become 0 per 3-vector, as core/predict/predictor.cpp does.
    auto finite = [](const Vec3& v) { return v.isFinite() ? v : Vec3(0.f); };
    bool haveDirect = false, haveIndirect = false;
    if (off[kSlotJoint] >= 0.f) {
        evaluateNetwork(r, findLeafNetwork(r, int(off[kSlotJoint]), raw), raw, y);
        terms[0] = finite(Vec3(y[0], y[1], y[2]));
        terms[1] = finite(Vec3(y[3], y[4], y[5]));
        haveDirect = haveIndirect = true;
    }
    if (off[kSlotDirect] >= 0.f) {
        evaluateNetwork(r, findLeafNetwork(r, int(off[kSlotDirect]), raw), raw, y);
        terms[0] = finite(Vec3(y[0], y[1], y[2]));
        haveDirect = true;
    }
    if (off[kSlotIndirect] >= 0.f) {
        evaluateNetwork(r, findLeafNetwork(r, int(off[kSlotIndirect]), raw), raw, y);
        terms[1] = finite(Vec3(y[0], y[1], y[2]));
        haveIndirect = true;
    }
    if (!(haveDirect && haveIndirect) && off[kSlotGlobal] >= 0.f) {
        evaluateNetwork(r, findLeafNetwork(r, int(off[kSlotGlobal]), raw), raw, y);
        terms[2] = finite(Vec3(y[0], y[1], y[2]));
    } else {
        terms[2] = terms[0] + terms[1];
    }
    return terms;
}

}  // namespace rrf
