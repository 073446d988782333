#pragma once
/// Multiresolution hash grid (Müller et al. 2022, instant-NGP; docs/design.md §10a): L grids of
/// growing resolution over d ≤ 4 normalised inputs (typically "position"); each grid vertex owns F
/// trainable features, found directly (coarse levels) or through a spatial hash into a table of T
/// entries (fine levels); an input's features are the d-linear interpolation of its cell's corners.
///
/// JSON: {"type": "hash_grid", "inputs": "position", "levels": L (1..24, default 16),
///        "log2_table_size": 10..22 (default 14), "features_per_level": F (1, 2, 4 or 8; default 2),
///        "base_resolution": 2..1024 (default 16), "growth": 1.0..4.0 (default 1.5)}
/// Also required: the finest resolution ≤ 2^24 (float positions stay exact) and L·T·F ≤ 2^27.
///
/// Formula (CPU float, CPU double and GLSL compute exactly this, in this order; the hash is fixed, so
/// indices are identical on every platform):
///   r_i   = (x_i + 1)·0.5;  u_i = r_i > 0 ? (r_i < 1 ? r_i : 1) : 0      i = 0 … d−1
///           (clamp to [0, 1] with NaN → 0: a NaN input gives finite features, never an index
///           outside the tables)
///   res_l = floor(b · g^l)   in double, g^l = g·g·…·g (l−1 products; g^0 = 1), an integer ≥ 2
///   s     = res_l (as S);  pos_i = u_i·s;  c_i = min(int(floor(pos_i)), res_l − 1);  f_i = pos_i − c_i
///   corner k = 0 … 2^d−1 (bit i of k = offset in dimension i), in increasing k:
///       v_i = c_i + bit_i(k);   w = Π_i (bit_i ? f_i : 1 − f_i)   (multiplied in increasing i)
///       T = 2^log2_table_size;  dense if (res_l + 1)^d ≤ T (exact 64-bit integers):
///           idx = Σ_i v_i·(res_l + 1)^i
///       else hashed:
///           idx = (XOR_i uint32(v_i)·π_i) & (T − 1),  uint32 wraparound,
///           π = {1, 2654435761, 805459861, 3674653429}
///   out[l·F + f] = Σ_k w_k · params[(l·T + idx_k)·F + f]   (accumulated in k order from 0)
/// numParams = L·T·F (every level has a table of T entries, dense or not; a dense level uses the
/// first (res_l + 1)^d of them).
///
/// Gradients: ∂out[l·F+f]/∂params[(l·T+idx_k)·F+f] = w_k; ∂/∂x_i = 0.5 · Σ_l s_l · Σ_k (Σ_f dOut·param)
/// · ∂w_k/∂f_i, and 0 where the clamp is active (r_i is outside [0, 1] or NaN). Within a cell
/// the map is smooth; across cell faces it is continuous with a kink.
///
/// Initial parameters: params[l·T·F + e] = (2·U − 1)·1e-4 with U = Rng(seed, stream, l)'s e-th
/// uniformDouble() (instant-NGP's U(−1e-4, 1e-4)); InputEncoding passes stream =
/// kEncodingStreamTag + network stream·16 + component (nn/encoding.h).

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/nn/encoding.h"
#include "core/nn/encodings/registry.h"

namespace rrf {

class HashGridEncoding final : public Encoding {
public:
    static constexpr int kMaxInputs = 4;
    static constexpr int kMaxLevels = 24;
    static constexpr int kMinLog2TableSize = 10, kMaxLog2TableSize = 22;
    static constexpr int kMinBaseResolution = 2, kMaxBaseResolution = 1024;
    static constexpr double kMaxGrowth = 4.0;
    /// Finest resolution allowed: positions u·res stay exact integers + fractions in float.
    static constexpr int64_t kMaxResolution = int64_t(1) << 24;
    /// Largest table (L·T·F): 512 MiB of float parameters.
    static constexpr int64_t kMaxParams = int64_t(1) << 27;
    /// The spatial hash's per-dimension multipliers (instant-NGP's primes; π_0 = 1 keeps coherence).
    static constexpr std::array<uint32_t, 4> kPrimes = {1u, 2654435761u, 805459861u, 3674653429u};

    /// Throws std::invalid_argument (naming the setting) unless 1 ≤ inputDims ≤ 4 and every setting
    /// is in range (see the JSON above).
    HashGridEncoding(int inputDims, HashGridSettings settings);

    const HashGridSettings& settings() const { return settings_; }
    /// T = 2^log2_table_size entries per level.
    int64_t tableSize() const { return int64_t(1) << settings_.log2TableSize; }
    /// res_l (the grid has res_l + 1 vertices per dimension).
    int levelResolution(int l) const { return levels_[size_t(l)].resolution; }
    /// True when level l is indexed directly ((res_l + 1)^d ≤ T), false when hashed.
    bool levelIsDense(int l) const { return levels_[size_t(l)].dense; }
    /// Table entry (0 … T−1) of vertex v (inputDims() coordinates, each in 0 … res_l) at level l.
    uint32_t entryIndex(int l, const int* v) const;

    /// Its component type in the network texture (shaders/encoding.glsl, predict/network_texture.h).
    static constexpr int kGlslId = 2;
    /// Its row of the encoding registry (encodings/registry.h).
    static const EncodingType& type();
    const char* typeName() const override { return type().name; }
    int inputDims() const override { return inputDims_; }
    int outputDims() const override { return settings_.levels * settings_.featuresPerLevel; }
    int64_t numParams() const override { return settings_.levels * tableSize() * settings_.featuresPerLevel; }
    void initParams(double* params, uint64_t seed, uint64_t stream) const override;

    void forward(const float* params, const Eigen::Ref<const MatX<float>>& x, Eigen::Ref<MatX<float>> out) const override;
    void forward(const double* params, const Eigen::Ref<const MatX<double>>& x, Eigen::Ref<MatX<double>> out) const override;
    void backwardParams(const float* params, const Eigen::Ref<const MatX<float>>& x,
                        const Eigen::Ref<const MatX<float>>& dOut, float* grad,
                        std::vector<int64_t>* touched) const override;
    void backwardParams(const double* params, const Eigen::Ref<const MatX<double>>& x,
                        const Eigen::Ref<const MatX<double>>& dOut, double* grad,
                        std::vector<int64_t>* touched) const override;
    void backwardInputs(const float* params, const Eigen::Ref<const MatX<float>>& x,
                        const Eigen::Ref<const MatX<float>>& dOut, Eigen::Ref<MatX<float>> dX) const override;
    void backwardInputs(const double* params, const Eigen::Ref<const MatX<double>>& x,
                        const Eigen::Ref<const MatX<double>>& dOut, Eigen::Ref<MatX<double>> dX) const override;

    EncodingParams params() const override { return settings_; }

private:
    struct Level {
        int resolution = 0;
        bool dense = false;
        std::array<uint32_t, kMaxInputs> stride{};  ///< (res + 1)^i, dense levels only
    };
    /// The cell of one sample at one level (formula above): per dimension the factors {1 − f_i, f_i}
    /// of the corner weights and the index terms of the lower and upper vertex
    /// ((c_i + b)·(res + 1)^i when dense, uint32(c_i + b)·π_i when hashed), so that each corner only
    /// sums or XORs d terms.
    template <typename S>
    struct Cell {
        S factor[kMaxInputs][2];
        uint32_t term[kMaxInputs][2];
    };
    template <typename S>
    Cell<S> cell(int l, const S* u) const;
    /// Interpolation weight of corner k of a cell (product in increasing i).
    template <typename S>
    S cornerWeight(const Cell<S>& cell, int k) const;
    /// Table entry of corner k of a cell at level l (equals entryIndex of its vertex).
    template <typename S>
    uint32_t cornerIndex(int l, const Cell<S>& cell, int k) const;

    template <typename S>
    void forwardImpl(const S* params, const Eigen::Ref<const MatX<S>>& x, Eigen::Ref<MatX<S>> out) const;
    template <typename S>
    void backwardParamsImpl(const Eigen::Ref<const MatX<S>>& x, const Eigen::Ref<const MatX<S>>& dOut, S* grad,
                            std::vector<int64_t>* touched) const;
    template <typename S>
    void backwardInputsImpl(const S* params, const Eigen::Ref<const MatX<S>>& x, const Eigen::Ref<const MatX<S>>& dOut,
                            Eigen::Ref<MatX<S>> dX) const;

    int inputDims_;
    HashGridSettings settings_;
    std::vector<Level> levels_;
};

}  // namespace rrf
