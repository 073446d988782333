#pragma once
/// Frequency (positional) encoding of NeRF (Mildenhall et al. 2020; docs/design.md §10a): each
/// normalised input becomes sines and cosines of geometrically growing frequencies, so that a small
/// MLP can represent detail far finer than its raw inputs allow.
///
/// JSON: {"type": "frequency", "inputs": ..., "frequencies": K (1..16, default 6),
///        "include_input": true|false (default true)}
///
/// Formula (CPU float, CPU double and GLSL compute exactly this, in this order). For input j of the
/// component (component order) the outputs are, consecutively,
///     [x_j                 if include_input]
///     sin(a_k), cos(a_k)   for k = 0 … K−1,   a_k = x_j · ω_k,   ω_k = π·2^k
/// where ω_k is computed in double and rounded once to the scalar type (float(π·2^k) for float).
/// outputDims = inputDims · (2K + include_input).
///
/// ∂/∂x_j: 1 for the copy, cos(a_k)·ω_k for the sine, −sin(a_k)·ω_k for the cosine.

#include <memory>

#include "core/nn/encoding.h"
#include "core/nn/encodings/registry.h"

namespace rrf {

class FrequencyEncoding final : public Encoding {
public:
    static constexpr int kMaxFrequencies = 16;

    /// Throws std::invalid_argument unless 1 ≤ inputDims and 1 ≤ K ≤ 16.
    FrequencyEncoding(int inputDims, FrequencySettings settings);

    const FrequencySettings& settings() const { return settings_; }
    /// ω_k = π·2^k computed in double and rounded once to S (the constant GLSL uses for float).
    template <typename S>
    static S angularFrequency(int k);

    /// Its component type in the network texture (shaders/encoding.glsl, predict/network_texture.h).
    static constexpr int kGlslId = 0;
    /// Its row of the encoding registry (encodings/registry.h).
    static const EncodingType& type();
    const char* typeName() const override { return type().name; }
    int inputDims() const override { return inputDims_; }
    int outputDims() const override { return inputDims_ * perInput(); }

    void forward(const float* params, const Eigen::Ref<const MatX<float>>& x, Eigen::Ref<MatX<float>> out) const override;
    void forward(const double* params, const Eigen::Ref<const MatX<double>>& x, Eigen::Ref<MatX<double>> out) const override;
    void backwardInputs(const float* params, const Eigen::Ref<const MatX<float>>& x,
                        const Eigen::Ref<const MatX<float>>& dOut, Eigen::Ref<MatX<float>> dX) const override;
    void backwardInputs(const double* params, const Eigen::Ref<const MatX<double>>& x,
                        const Eigen::Ref<const MatX<double>>& dOut, Eigen::Ref<MatX<double>> dX) const override;

    EncodingParams params() const override { return settings_; }

private:
    /// Outputs per input: 2K + include_input.
    int perInput() const { return 2 * settings_.frequencies + (settings_.includeInput ? 1 : 0); }
    template <typename S>
    void forwardImpl(const Eigen::Ref<const MatX<S>>& x, Eigen::Ref<MatX<S>> out) const;
    template <typename S>
    void backwardInputsImpl(const Eigen::Ref<const MatX<S>>& x, const Eigen::Ref<const MatX<S>>& dOut,
                            Eigen::Ref<MatX<S>> dX) const;

    int inputDims_;
    FrequencySettings settings_;
};

}  // namespace rrf
