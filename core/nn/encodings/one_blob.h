#pragma once
/// One-blob encoding (Müller et al. 2019, "Neural Importance Sampling"; used by Neural Radiance
/// Caching 2021; docs/design.md §10a): each bounded input becomes B Gaussian "blobs" on a regular
/// grid over its range, a smooth one-hot code that lets a small MLP switch behaviour by input value.
///
/// JSON: {"type": "one_blob", "inputs": ..., "bins": B (2..64, default 16)}
///
/// Formula (CPU float, CPU double and GLSL compute exactly this, in this order). For input j of the
/// component (component order) the outputs are, consecutively, for k = 0 … B−1:
///     u   = clamp((x_j + 1)·0.5, 0, 1)
///     c_k = (k + 0.5) / B                  (float(k) + 0.5, divided by float(B))
///     t   = (u − c_k)·B
///     out = exp(−0.5·t·t)                  ((−0.5·t)·t; σ = 1/B in u)
/// outputDims = inputDims · B.
///
/// ∂/∂x_j = Σ_k dOut_k · (−t·out_k) · B · 0.5, and 0 where the clamp is active (the unclamped u is
/// outside [0, 1]).

#include <memory>

#include "core/nn/encoding.h"
#include "core/nn/encodings/registry.h"

namespace rrf {

class OneBlobEncoding final : public Encoding {
public:
    static constexpr int kMinBins = 2;
    static constexpr int kMaxBins = 64;

    /// Throws std::invalid_argument unless 1 ≤ inputDims and 2 ≤ B ≤ 64.
    OneBlobEncoding(int inputDims, OneBlobSettings settings);

    const OneBlobSettings& settings() const { return settings_; }

    /// Its component type in the network texture (shaders/encoding.glsl, predict/network_texture.h).
    static constexpr int kGlslId = 1;
    /// Its row of the encoding registry (encodings/registry.h).
    static const EncodingType& type();
    const char* typeName() const override { return type().name; }
    int inputDims() const override { return inputDims_; }
    int outputDims() const override { return inputDims_ * settings_.bins; }

    void forward(const float* params, const Eigen::Ref<const MatX<float>>& x, Eigen::Ref<MatX<float>> out) const override;
    void forward(const double* params, const Eigen::Ref<const MatX<double>>& x, Eigen::Ref<MatX<double>> out) const override;
    void backwardInputs(const float* params, const Eigen::Ref<const MatX<float>>& x,
                        const Eigen::Ref<const MatX<float>>& dOut, Eigen::Ref<MatX<float>> dX) const override;
    void backwardInputs(const double* params, const Eigen::Ref<const MatX<double>>& x,
                        const Eigen::Ref<const MatX<double>>& dOut, Eigen::Ref<MatX<double>> dX) const override;

    EncodingParams params() const override { return settings_; }

private:
    template <typename S>
    void forwardImpl(const Eigen::Ref<const MatX<S>>& x, Eigen::Ref<MatX<S>> out) const;
    template <typename S>
    void backwardInputsImpl(const Eigen::Ref<const MatX<S>>& x, const Eigen::Ref<const MatX<S>>& dOut,
                            Eigen::Ref<MatX<S>> dX) const;

    int inputDims_;
    OneBlobSettings settings_;
};

}  // namespace rrf
