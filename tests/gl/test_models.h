#pragma once
/// Test networks for the GLSL predictor: untrained networks with realistic weights (the trainer's own
/// Nguyen–Widrow / Glorot initialisation) and mapminmax scalers fitted on plausible inputs and
/// outputs, plus the CPU reference prediction computed with NetworkModel::predict. Equivalence does
/// not depend on the weights being good, only on both sides evaluating the same network.

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "core/nn/encoding.h"
#include "core/nn/encoding_json.h"
#include "core/nn/model_set.h"
#include "core/util/json_reader.h"
#include "core/data/record_layout.h"
#include "core/scene/scene.h"
#include "core/scene/scene_json.h"

namespace rrf::test {

inline Scene cornellBox() { return loadScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/scene.json"); }

/// Uniform in [0, 1) from a small LCG (tests must not depend on core's Rng interface details).
class TestRandom {
public:
    explicit TestRandom(uint64_t seed) : s_(seed * 0x9E3779B97F4A7C15ull + 1) {}
    float uniform() {
        s_ = s_ * 6364136223846793005ull + 1442695040888963407ull;
        return float(s_ >> 40) / float(1ull << 24);
    }
    float range(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    Vec3 unitVector() {
        for (;;) {
            const Vec3 v(range(-1, 1), range(-1, 1), range(-1, 1));
            const float l = length(v);
            if (l > 0.1f && l <= 1.f) return v / l;
        }
    }

private:
    uint64_t s_;
};

/// A network for `target` of object `objectId` with inputs fitted on the scene's ranges; with
/// `derived` inputs (nn/derived_inputs.h) it reads them after the record's, scaled on their ranges.
inline NetworkModel randomNetwork(const Scene& scene, int objectId, const std::string& target, std::vector<int> hidden,
                                  Activation act, uint64_t seed, const DerivedInputs& derived = {}) {
    const RecordLayout layout = RecordLayout::forScene(scene);
    NetworkModel m;
    m.encoding.inputs = layout.inputCount();
    m.encoding.derived = derived;
    m.arch.inputs = layout.inputCount() + derived.count();
    m.arch.hidden = std::move(hidden);
    m.arch.outputs = target == "joint" ? 6 : 3;
    m.arch.activation = act;
    m.params = initialParams(m.arch, seed, uint64_t(objectId) * 4 + uint64_t(target.size()));
    m.objectId = objectId;
    m.target = target;

    TestRandom rnd(seed * 131 + uint64_t(objectId));
    const Bounds3 b = scene.bounds();
    const Bounds3 region = scene.lightRegion.empty() ? b : scene.lightRegion;
    const int n = 64;
    MatX<float> in(layout.inputCount(), n), out(m.arch.outputs, n);
    float brdf[8] = {};
    layout.brdfParameters(scene.materials[size_t(scene.objects[size_t(objectId)].material)], brdf);
    for (int c = 0; c < n; ++c) {
        const Vec3 p(rnd.range(b.lo.x, b.hi.x), rnd.range(b.lo.y, b.hi.y), rnd.range(b.lo.z, b.hi.z));
        const Vec3 v = rnd.unitVector(), nn = rnd.unitVector();
        const Vec3 l(rnd.range(region.lo.x, region.hi.x), rnd.range(region.lo.y, region.hi.y),
                     rnd.range(region.lo.z, region.hi.z));
        const Vec3 f[4] = {p, v, l, nn};
        for (int k = 0; k < 12; ++k) in(k, c) = f[k / 3][k % 3];
        // BRDF inputs are constant per object: exercises mapminmax's constant-feature rule.
        for (int k = 12; k < layout.inputCount(); ++k) in(k, c) = brdf[k - 12];
        // Radiance-like targets: the Cornell box's direct and indirect radiance lie within [0, 1.5].
        for (int k = 0; k < m.arch.outputs; ++k) out(k, c) = rnd.range(0.f, 1.f + 0.1f * float(k));
    }
    MatX<float> withDerived;
    derived.append<float>(in, withDerived);
    m.inputScaler = MinMaxScaler::fit(withDerived);
    m.outputScaler = MinMaxScaler::fit(out);
    m.validate();
    return m;
}

/// randomNetwork reading its inputs through `encoding` (an "encoding" array, nn/encoding.h): the
/// first layer sized for the encoding's features, hash tables uniform in [−1, 1] (far larger than a
/// fresh instant-NGP table, so that every table entry read moves the outputs).
inline NetworkModel encodedNetwork(const Scene& scene, int objectId, const std::string& target, std::vector<int> hidden,
                                   Activation act, uint64_t seed, const nlohmann::json& encoding,
                                   const DerivedInputs& derived = {}) {
    NetworkModel m = randomNetwork(scene, objectId, target, std::move(hidden), act, seed, derived);
    m.encoding = inputEncodingFromJson(JsonReader(encoding, "test encoding"), m.rawInputs(), derived);
    m.arch.inputs = m.encoding.outputs();
    m.params = initialParams(m.arch, seed, uint64_t(objectId) * 4 + uint64_t(target.size()));
    TestRandom rnd(seed * 977 + uint64_t(objectId));
    m.encodingParams.resize(m.encoding.numParams());
    for (Eigen::Index i = 0; i < m.encodingParams.size(); ++i) m.encodingParams[i] = double(rnd.range(-1.f, 1.f));
    m.validate();
    return m;
}

/// Per object a different mix of targets, so that every combination rule of the shader is exercised:
/// joint; direct + indirect; global only; global + direct + indirect (global net unused); global +
/// indirect (global net used); direct only.
/// With `encoding` (an "encoding" array, nn/encoding.h), every network reads its inputs through it
/// (encodedNetwork).
/// With `derived` inputs, every network derives them (randomNetwork).
inline ModelSet mixedModelSet(const Scene& scene, Activation act = Activation::Tanh, std::vector<int> hidden = {20, 10},
                              uint64_t seed = 7, const nlohmann::json& encoding = nlohmann::json::array(),
                              const DerivedInputs& derived = {}) {
    static const std::vector<std::vector<std::string>> mixes = {
        {"joint"}, {"direct", "indirect"}, {"global"}, {"global", "direct", "indirect"}, {"global", "indirect"}, {"direct"}};
    ModelSet set;
    set.inputLayout = RecordLayout::forScene(scene).inputs;
    for (const Object& o : scene.objects) {
        ObjectNetworks on;
        on.objectId = o.id;
        on.name = o.name;
        for (const std::string& t : mixes[size_t(o.id) % mixes.size()])
            on.byTarget[t] = encoding.empty() ? randomNetwork(scene, o.id, t, hidden, act, seed, derived)
                                              : encodedNetwork(scene, o.id, t, hidden, act, seed, encoding, derived);
        set.objects.push_back(std::move(on));
    }
    return set;
}

/// mixedModelSet with every model a kd-tree of three leaves (nn/partition_tree.h): hit_x < splitX
/// → leaf 0, else light_x < splitLightX → leaf 1, else leaf 2; each leaf a different random network.
inline ModelSet partitionedModelSet(const Scene& scene, float splitX, float splitLightX, uint64_t seed = 11) {
    ModelSet set = mixedModelSet(scene);
    for (ObjectNetworks& on : set.objects)
        for (auto& [target, model] : on.byTarget) {
            PartitionedNetwork t;
            t.tree.nodes.resize(5);
            t.tree.nodes[0] = {0, splitX, 1, 2};
            t.tree.nodes[1].leaf = 0;
            t.tree.nodes[2] = {6, splitLightX, 3, 4};
            t.tree.nodes[3].leaf = 1;
            t.tree.nodes[4].leaf = 2;
            for (uint64_t l = 0; l < 3; ++l)
                t.leaves.push_back(randomNetwork(scene, on.objectId, target, model.arch().hidden, Activation::Tanh,
                                                 seed + 17 * l));
            t.validate();
            model = std::move(t);
        }
    return set;
}

/// CPU reference: direct, indirect, global of one object for raw inputs (inputs × N), combined by the
/// rules of core/predict/network_texture.h but computed with PartitionedNetwork::predict (S = float)
/// or PartitionedNetwork::predictDouble (S = double, to measure how far float itself is from exact);
/// both look the leaf up on the float inputs.
template <typename S> struct CpuTermsT {
    MatX<S> direct, indirect, global;
};
using CpuTerms = CpuTermsT<float>;

template <typename S> MatX<S> predictAs(const PartitionedNetwork& m, const MatX<S>& raw) {
    if constexpr (std::is_same_v<S, float>)
        return m.predict(raw);
    else
        return m.predictDouble(raw);
}

template <typename S> CpuTermsT<S> cpuTerms(const ObjectNetworks& on, const MatX<S>& raw) {
    const Eigen::Index n = raw.cols();
    CpuTermsT<S> t{MatX<S>::Zero(3, n), MatX<S>::Zero(3, n), MatX<S>::Zero(3, n)};
    if (on.has("joint")) {
        const MatX<S> y = predictAs(on.byTarget.at("joint"), raw);
        t.direct = y.topRows(3);
        t.indirect = y.bottomRows(3);
    }
    if (on.has("direct")) t.direct = predictAs(on.byTarget.at("direct"), raw);
    if (on.has("indirect")) t.indirect = predictAs(on.byTarget.at("indirect"), raw);
    const bool both = (on.has("direct") || on.has("joint")) && (on.has("indirect") || on.has("joint"));
    if (!both && on.has("global"))
        t.global = predictAs(on.byTarget.at("global"), raw);
    else
        t.global = t.direct + t.indirect;
    return t;
}

/// The acceptance rule of issue 6: relative difference ≤ 1e-4 with an absolute floor for outputs near 0.
inline bool closeEnough(float gl, float cpu, float rel = 1e-4f, float floor = 1e-2f) {
    return std::fabs(gl - cpu) <= rel * std::max(std::fabs(cpu), floor);
}

}  // namespace rrf::test
