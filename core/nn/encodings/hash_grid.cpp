#include "core/nn/encodings/hash_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/util/text_format.h"
#include "core/util/rng.h"

namespace rrf {

namespace {

std::string settingRange(const char* name, double v, double lo, double hi) {
    return std::string(name) + " must be in [" + formatNumber(lo) + ", " + formatNumber(hi) + "], got " +
           formatNumber(v);
}

/// u = clamp((x + 1)·0.5, 0, 1) of a sample's inputs, NaN → 0; `clamped[i]` says the clamp is
/// active (also for NaN). Written as comparisons because std::clamp(NaN) is NaN, and floor(NaN)
/// converted to int (the cell index) is undefined: it read outside the tables.
template <typename S>
void unitCoordinates(const Eigen::Ref<const MatX<S>>& x, Eigen::Index n, int d, S* u, bool* clamped = nullptr) {
    for (int i = 0; i < d; ++i) {
        const S raw = (x(i, n) + S(1)) * S(0.5);
        u[i] = raw > S(0) ? (raw < S(1) ? raw : S(1)) : S(0);
        if (clamped) clamped[i] = !(raw >= S(0) && raw <= S(1));
    }
}

}  // namespace

HashGridEncoding::HashGridEncoding(int inputDims, HashGridSettings s) : inputDims_(inputDims), settings_(s) {
    if (inputDims < 1 || inputDims > kMaxInputs)
        throw std::invalid_argument(std::string(type().name) + " reads 1 to " + std::to_string(kMaxInputs) + " inputs, got " +
                                    std::to_string(inputDims));
    if (s.levels < 1 || s.levels > kMaxLevels) throw std::invalid_argument(settingRange("levels", s.levels, 1, kMaxLevels));
    if (s.log2TableSize < kMinLog2TableSize || s.log2TableSize > kMaxLog2TableSize)
        throw std::invalid_argument(settingRange("log2_table_size", s.log2TableSize, kMinLog2TableSize, kMaxLog2TableSize));
    if (s.featuresPerLevel != 1 && s.featuresPerLevel != 2 && s.featuresPerLevel != 4 && s.featuresPerLevel != 8)
        throw std::invalid_argument("features_per_level must be 1, 2, 4 or 8, got " + std::to_string(s.featuresPerLevel));
    if (s.baseResolution < kMinBaseResolution || s.baseResolution > kMaxBaseResolution)
        throw std::invalid_argument(
            settingRange("base_resolution", s.baseResolution, kMinBaseResolution, kMaxBaseResolution));
    if (!(s.growth >= 1.0 && s.growth <= kMaxGrowth)) throw std::invalid_argument(settingRange("growth", s.growth, 1.0, kMaxGrowth));
    if (numParams() > kMaxParams)
        throw std::invalid_argument("levels · 2^log2_table_size · features_per_level = " + std::to_string(numParams()) +
                                    " parameters, more than the " + std::to_string(kMaxParams) + " allowed");

    const uint64_t T = uint64_t(tableSize());
    double power = 1.0;  // g^l by successive products: IEEE double, identical on every platform
    for (int l = 0; l < s.levels; ++l) {
        if (l > 0) power *= s.growth;
        const double res = std::floor(double(s.baseResolution) * power);
        if (res > double(kMaxResolution))
            throw std::invalid_argument("level " + std::to_string(l) + " has resolution " + formatNumber(res) +
                                        ", more than 2^24 (lower levels, base_resolution or growth)");
        Level level;
        level.resolution = int(res);
        // (res + 1)^d ≤ T, multiplied out in 64 bits with an early exit (no overflow for d ≤ 4).
        uint64_t vertices = 1;
        level.dense = true;
        for (int i = 0; i < inputDims; ++i) {
            level.stride[size_t(i)] = uint32_t(vertices);  // ≤ T: the loop stops once above it
            vertices *= uint64_t(level.resolution) + 1;
            if (vertices > T) {
                level.dense = false;
                break;
            }
        }
        levels_.push_back(level);
    }
}

const EncodingType& HashGridEncoding::type() {
    static const EncodingType t{"hash_grid", {"levels", "log2_table_size", "features_per_level", "base_resolution", "growth"}, kMaxInputs, kGlslId,
                                [](const EncodingParams& s, int inputDims) -> std::shared_ptr<const Encoding> {
                                    return std::make_shared<const HashGridEncoding>(inputDims, std::get<HashGridSettings>(s));
                                }};
    return t;
}

uint32_t HashGridEncoding::entryIndex(int l, const int* v) const {
    const Level& level = levels_[size_t(l)];
    if (level.dense) {
        uint32_t idx = 0;
        for (int i = 0; i < inputDims_; ++i) idx += uint32_t(v[i]) * level.stride[size_t(i)];
        return idx;
    }
    uint32_t h = 0;
    for (int i = 0; i < inputDims_; ++i) h ^= uint32_t(v[i]) * kPrimes[size_t(i)];
    return h & uint32_t(tableSize() - 1);
}

template <typename S>
uint32_t HashGridEncoding::cornerIndex(int l, const Cell<S>& cl, int k) const {
    if (levels_[size_t(l)].dense) {
        uint32_t idx = cl.term[0][k & 1];
        for (int i = 1; i < inputDims_; ++i) idx += cl.term[i][(k >> i) & 1];
        return idx;
    }
    uint32_t h = cl.term[0][k & 1];
    for (int i = 1; i < inputDims_; ++i) h ^= cl.term[i][(k >> i) & 1];
    return h & uint32_t(tableSize() - 1);
}

template <typename S>
HashGridEncoding::Cell<S> HashGridEncoding::cell(int l, const S* u) const {
    const Level& level = levels_[size_t(l)];
    const int res = level.resolution;
    const S s = S(res);
    Cell<S> cl;
    for (int i = 0; i < inputDims_; ++i) {
        const S pos = u[i] * s;
        const int c = std::min(int(std::floor(pos)), res - 1);
        const S f = pos - S(c);
        cl.factor[i][0] = S(1) - f;
        cl.factor[i][1] = f;
        for (int b = 0; b < 2; ++b)
            cl.term[i][b] = level.dense ? uint32_t(c + b) * level.stride[size_t(i)] : uint32_t(c + b) * kPrimes[size_t(i)];
    }
    return cl;
}

template <typename S>
S HashGridEncoding::cornerWeight(const Cell<S>& cl, int k) const {
    S w = cl.factor[0][k & 1];
    for (int i = 1; i < inputDims_; ++i) w *= cl.factor[i][(k >> i) & 1];
    return w;
}

void HashGridEncoding::initParams(double* params, uint64_t seed, uint64_t stream) const {
    const int64_t perLevel = tableSize() * settings_.featuresPerLevel;
    for (int l = 0; l < settings_.levels; ++l) {
        Rng rng(seed, stream, uint64_t(l));
        double* p = params + int64_t(l) * perLevel;
        for (int64_t e = 0; e < perLevel; ++e) p[e] = (2.0 * rng.uniformDouble() - 1.0) * 1e-4;
    }
}

// The passes loop over levels outside and samples inside: one level's table (T·F values) stays in
// cache while every sample reads it, instead of all L tables competing for it per sample. The
// arithmetic per (sample, level) and its order are those of the formula.

template <typename S>
void HashGridEncoding::forwardImpl(const S* params, const Eigen::Ref<const MatX<S>>& x, Eigen::Ref<MatX<S>> out) const {
    const int F = settings_.featuresPerLevel, corners = 1 << inputDims_;
    const int64_t T = tableSize();
    S u[kMaxInputs];
    for (int l = 0; l < settings_.levels; ++l) {
        const S* table = params + int64_t(l) * T * F;
        for (Eigen::Index n = 0; n < x.cols(); ++n) {
            unitCoordinates<S>(x, n, inputDims_, u);
            const Cell<S> cl = cell<S>(l, u);
            S acc[8] = {};
            for (int k = 0; k < corners; ++k) {
                const S w = cornerWeight<S>(cl, k);
                const S* p = table + int64_t(cornerIndex<S>(l, cl, k)) * F;
                for (int f = 0; f < F; ++f) acc[f] += w * p[f];
            }
            for (int f = 0; f < F; ++f) out(l * F + f, n) = acc[f];
        }
    }
}

template <typename S>
void HashGridEncoding::backwardParamsImpl(const Eigen::Ref<const MatX<S>>& x, const Eigen::Ref<const MatX<S>>& dOut,
                                          S* grad, std::vector<int64_t>* touched) const {
    const int F = settings_.featuresPerLevel, corners = 1 << inputDims_;
    const int64_t T = tableSize();
    if (touched) touched->reserve(touched->size() + size_t(x.cols()) * size_t(settings_.levels * corners * F));
    S u[kMaxInputs];
    for (int l = 0; l < settings_.levels; ++l) {
        for (Eigen::Index n = 0; n < x.cols(); ++n) {
            unitCoordinates<S>(x, n, inputDims_, u);
            const Cell<S> cl = cell<S>(l, u);
            for (int k = 0; k < corners; ++k) {
                const S w = cornerWeight<S>(cl, k);
                const int64_t base = (int64_t(l) * T + cornerIndex<S>(l, cl, k)) * F;
                for (int f = 0; f < F; ++f) {
                    grad[base + f] += w * dOut(l * F + f, n);
                    if (touched) touched->push_back(base + f);
                }
            }
        }
    }
}

template <typename S>
void HashGridEncoding::backwardInputsImpl(const S* params, const Eigen::Ref<const MatX<S>>& x,
                                          const Eigen::Ref<const MatX<S>>& dOut, Eigen::Ref<MatX<S>> dX) const {
    const int F = settings_.featuresPerLevel, corners = 1 << inputDims_;
    const int64_t T = tableSize();
    S u[kMaxInputs];
    dX.setZero();  // accumulates ∂loss/∂u_i over the levels, in level order
    for (int l = 0; l < settings_.levels; ++l) {
        const S* table = params + int64_t(l) * T * F;
        const S s = S(levels_[size_t(l)].resolution);
        for (Eigen::Index n = 0; n < x.cols(); ++n) {
            unitCoordinates<S>(x, n, inputDims_, u);
            const Cell<S> cl = cell<S>(l, u);
            for (int k = 0; k < corners; ++k) {
                // g = Σ_f dOut·param: how much the loss changes per unit of this corner's weight.
                const S* p = table + int64_t(cornerIndex<S>(l, cl, k)) * F;
                S g = 0;
                for (int f = 0; f < F; ++f) g += dOut(l * F + f, n) * p[f];
                for (int i = 0; i < inputDims_; ++i) {
                    // ∂w/∂f_i: the other factors, with sign + for the upper and − for the lower corner.
                    S dw = ((k >> i) & 1) ? S(1) : S(-1);
                    for (int j = 0; j < inputDims_; ++j)
                        if (j != i) dw *= cl.factor[j][(k >> j) & 1];
                    dX(i, n) += g * dw * s;
                }
            }
        }
    }
    bool clamped[kMaxInputs];
    for (Eigen::Index n = 0; n < x.cols(); ++n) {
        unitCoordinates<S>(x, n, inputDims_, u, clamped);
        for (int i = 0; i < inputDims_; ++i) dX(i, n) = clamped[i] ? S(0) : dX(i, n) * S(0.5);
    }
}

void HashGridEncoding::forward(const float* params, const Eigen::Ref<const MatX<float>>& x,
                               Eigen::Ref<MatX<float>> out) const {
    forwardImpl<float>(params, x, out);
}
void HashGridEncoding::forward(const double* params, const Eigen::Ref<const MatX<double>>& x,
                               Eigen::Ref<MatX<double>> out) const {
    forwardImpl<double>(params, x, out);
}
void HashGridEncoding::backwardParams(const float*, const Eigen::Ref<const MatX<float>>& x,
                                      const Eigen::Ref<const MatX<float>>& dOut, float* grad,
                                      std::vector<int64_t>* touched) const {
    backwardParamsImpl<float>(x, dOut, grad, touched);
}
void HashGridEncoding::backwardParams(const double*, const Eigen::Ref<const MatX<double>>& x,
                                      const Eigen::Ref<const MatX<double>>& dOut, double* grad,
                                      std::vector<int64_t>* touched) const {
    backwardParamsImpl<double>(x, dOut, grad, touched);
}
void HashGridEncoding::backwardInputs(const float* params, const Eigen::Ref<const MatX<float>>& x,
                                      const Eigen::Ref<const MatX<float>>& dOut, Eigen::Ref<MatX<float>> dX) const {
    backwardInputsImpl<float>(params, x, dOut, dX);
}
void HashGridEncoding::backwardInputs(const double* params, const Eigen::Ref<const MatX<double>>& x,
                                      const Eigen::Ref<const MatX<double>>& dOut, Eigen::Ref<MatX<double>> dX) const {
    backwardInputsImpl<double>(params, x, dOut, dX);
}

}  // namespace rrf
