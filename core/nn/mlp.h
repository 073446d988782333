#pragma once
/// Multi-layer perceptron used as a radiance regression function (Ren et al. 2013; docs/design.md §10).
///
/// A network is `inputs → hidden[0] → … → hidden[k-1] → outputs`: affine layers, tanh (or ReLU)
/// after every hidden layer and a linear output layer. All parameters live in ONE flat vector so that
/// the Levenberg–Marquardt step `Δw = −(JᵀJ + μI)⁻¹ Jᵀe` and the Adam update are plain vector
/// operations; layer l occupies `[weightOffset(l), weightOffset(l) + out·in)` for its weight matrix
/// W_l (out × in, column-major, as Eigen stores it) followed by its bias b_l (out).
///
/// Data are Eigen matrices with one sample per COLUMN (features × N). A column-major features × N
/// matrix has the same memory layout as N records of `features` floats one after another, so a
/// dataset's record array maps onto it without a copy, and every layer is one GEMM `W · A`.
///
/// The network works in normalised units; MinMaxScaler maps raw inputs and targets to [-1, 1]
/// (Matlab's mapminmax). Forward, backward and Jacobian routines are templated on the scalar type and
/// instantiated for float (Adam, inference) and double (Levenberg–Marquardt, finite-difference tests).

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace rrf {

template <typename S> using MatX = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
template <typename S> using VecX = Eigen::Matrix<S, Eigen::Dynamic, 1>;

/// Nonlinearity of the hidden layers (the output layer is always linear).
enum class Activation { Tanh, Relu };

/// "tanh" / "relu".
const char* activationName(Activation a);
/// Parses "tanh" / "relu"; throws std::invalid_argument on anything else.
Activation parseActivation(const std::string& name);

/// Shape of a network and the layout of its flat parameter vector.
struct MlpArch {
    int inputs = 0;                ///< 12 + n for RRF records (position, view, light, normal, BRDF)
    std::vector<int> hidden{20, 10};  ///< the report's network; a project's default is NetworkOptions::hidden
    int outputs = 3;               ///< 3 (one RGB target) or 6 (direct and indirect RGB)
    Activation activation = Activation::Tanh;

    int numLayers() const { return int(hidden.size()) + 1; }
    int layerInputs(int l) const { return l == 0 ? inputs : hidden[size_t(l - 1)]; }
    int layerOutputs(int l) const { return l == numLayers() - 1 ? outputs : hidden[size_t(l)]; }
    /// Start of W_l (out × in, column-major) in the flat parameter vector.
    Eigen::Index weightOffset(int l) const;
    /// Start of b_l, directly after W_l.
    Eigen::Index biasOffset(int l) const { return weightOffset(l) + Eigen::Index(layerOutputs(l)) * layerInputs(l); }
    /// Total number of weights and biases (P).
    Eigen::Index numParams() const;
    /// Multiply–adds of one forward pass for one sample (Σ in·out).
    double macsPerSample() const;
    /// Throws std::invalid_argument unless all sizes are positive and within sane bounds.
    void validate() const;
    /// "16-20-10-3 tanh".
    std::string describe() const;

    bool operator==(const MlpArch& o) const {
        return inputs == o.inputs && hidden == o.hidden && outputs == o.outputs && activation == o.activation;
    }
};

/// Initial parameters, a pure function of (arch, seed): Nguyen–Widrow for tanh hidden layers (as
/// Matlab's initnw, so LM starts where trainlm starts), He-uniform for ReLU layers and Glorot-uniform
/// for the linear output layer. Every number comes from Rng(seed, 128·stream + layer, unit), so
/// networks of different objects (streams) start differently from one seed.
VecX<double> initialParams(const MlpArch& arch, uint64_t seed, uint64_t stream = 0);

/// Per-feature affine map onto [-1, 1] fitted on training data (mapminmax):
/// `normalised = (raw − offset) · scale`, `raw = normalised / scale + offset`.
/// A constant feature — exactly, or within float rounding (range ≤ 1e-5 of its magnitude) — gets
/// scale 1 and offset = its minimum, so it maps to (about) 0 and back exactly; nothing is ever
/// divided by zero, and rounding noise is never amplified into a full-range input.
struct MinMaxScaler {
    VecX<double> offset, scale;

    Eigen::Index size() const { return offset.size(); }
    /// Fits on the columns of `data` (features × N). N may be 0 (identity map) or 1 (all constant).
    static MinMaxScaler fit(const Eigen::Ref<const MatX<float>>& data);
    /// Identity map for `features` features.
    static MinMaxScaler identity(Eigen::Index features);

    /// In place: raw → normalised.
    template <typename S> void apply(MatX<S>& m) const;
    /// In place: normalised → raw.
    template <typename S> void invert(MatX<S>& m) const;
};

/// Forward pass on normalised inputs `x` (inputs × N). On return `acts[l]` (l = 0 … L−1) holds the
/// output of layer l after its nonlinearity; `acts.back()` is the network output (outputs × N).
/// `acts` is reused between calls to avoid reallocations.
template <typename S>
void mlpForward(const MlpArch& arch, const S* params, const Eigen::Ref<const MatX<S>>& x,
                std::vector<MatX<S>>& acts);

/// Backward pass after mlpForward on the same `x`. `dOut` (outputs × N) is ∂loss/∂output; on return
/// `grad` (P entries) holds ∂loss/∂params summed over the N samples. `deltas` is scratch space.
/// When `dInputs` is given it receives ∂loss/∂x (inputs × N, the first layer's deltas through W₀ᵀ):
/// what a trainable input encoding (nn/encoding.h) back-propagates into its parameters.
template <typename S>
void mlpBackward(const MlpArch& arch, const S* params, const Eigen::Ref<const MatX<S>>& x,
                 const std::vector<MatX<S>>& acts, const MatX<S>& dOut, std::vector<MatX<S>>& deltas,
                 S* grad, MatX<S>* dInputs = nullptr);

/// Jacobian rows of the outputs w.r.t. the parameters, after mlpForward on the same `x` (N samples).
/// On return `jt` is P × (N·outputs); column `k·N + n` is ∂output_k(sample n)/∂params, i.e. one row
/// of J stored as a column so that JᵀJ is the rank update `jt · jtᵀ`. `deltas` is scratch space.
template <typename S>
void mlpJacobianT(const MlpArch& arch, const S* params, const Eigen::Ref<const MatX<S>>& x,
                  const std::vector<MatX<S>>& acts, std::vector<MatX<S>>& deltas, MatX<S>& jt);

}  // namespace rrf
