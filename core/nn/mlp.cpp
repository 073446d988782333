#include "core/nn/mlp.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/nn/mlp_isa.h"
#include "core/nn/mlp_kernel.h"
#include "core/util/rng.h"

namespace rrf {

const char* activationName(Activation a) { return a == Activation::Relu ? "relu" : "tanh"; }

Activation parseActivation(const std::string& name) {
    if (name == "tanh") return Activation::Tanh;
    if (name == "relu") return Activation::Relu;
    throw std::invalid_argument("unknown activation '" + name + "' (expected \"tanh\" or \"relu\")");
}

Eigen::Index MlpArch::weightOffset(int l) const {
    Eigen::Index off = 0;
    for (int i = 0; i < l; ++i) off += Eigen::Index(layerOutputs(i)) * (layerInputs(i) + 1);
    return off;
}

Eigen::Index MlpArch::numParams() const { return weightOffset(numLayers()); }

double MlpArch::macsPerSample() const {
    double m = 0;
    for (int l = 0; l < numLayers(); ++l) m += double(layerInputs(l)) * layerOutputs(l);
    return m;
}

void MlpArch::validate() const {
    // Bounds keep P·P (LM) and per-layer GEMMs far from integer overflow.
    constexpr int kMaxWidth = 1 << 16;
    if (inputs < 1 || inputs > kMaxWidth)
        throw std::invalid_argument("network inputs must be in [1, 65536], got " + std::to_string(inputs));
    if (outputs < 1 || outputs > kMaxWidth)
        throw std::invalid_argument("network outputs must be in [1, 65536], got " + std::to_string(outputs));
    if (hidden.size() > 64) throw std::invalid_argument("at most 64 hidden layers are supported");
    for (size_t i = 0; i < hidden.size(); ++i)
        if (hidden[i] < 1 || hidden[i] > kMaxWidth)
            throw std::invalid_argument("hidden layer " + std::to_string(i) + " must have 1 … 65536 units, got " +
                                        std::to_string(hidden[i]));
}

std::string MlpArch::describe() const {
    std::string s = std::to_string(inputs);
    for (int h : hidden) s += "-" + std::to_string(h);
    return s + "-" + std::to_string(outputs) + " " + activationName(activation);
}

namespace {

double gaussian(Rng& rng) {
    const double u1 = 1.0 - rng.uniformDouble();  // (0, 1]: log stays finite
    const double u2 = rng.uniformDouble();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

}  // namespace

VecX<double> initialParams(const MlpArch& arch, uint64_t seed, uint64_t stream) {
    arch.validate();
    VecX<double> p(arch.numParams());
    for (int l = 0; l < arch.numLayers(); ++l) {
        const int in = arch.layerInputs(l), out = arch.layerOutputs(l);
        Eigen::Map<MatX<double>> W(p.data() + arch.weightOffset(l), out, in);
        Eigen::Map<VecX<double>> b(p.data() + arch.biasOffset(l), out);
        const bool hiddenLayer = l + 1 < arch.numLayers();
        if (hiddenLayer && arch.activation == Activation::Tanh) {
            // Nguyen–Widrow: random unit directions scaled to 0.7·S^(1/R), biases spread evenly so
            // the units' active regions tile the normalised input range [-1, 1]^R.
            const double mag = 0.7 * std::pow(double(out), 1.0 / in);
            for (int i = 0; i < out; ++i) {
                Rng rng(seed, stream * 128 + uint64_t(l), uint64_t(i));
                double norm2 = 0;
                for (int j = 0; j < in; ++j) {
                    W(i, j) = gaussian(rng);
                    norm2 += W(i, j) * W(i, j);
                }
                const double s = norm2 > 0 ? mag / std::sqrt(norm2) : 0.0;
                W.row(i) *= s;
                const double spread = out > 1 ? -1.0 + 2.0 * i / (out - 1) : 0.0;
                b(i) = mag * spread * (W(i, 0) < 0 ? -1.0 : 1.0);
            }
        } else {
            // He-uniform for ReLU (keeps activation variance), Glorot-uniform for the linear output.
            const double limit = hiddenLayer ? std::sqrt(6.0 / in) : std::sqrt(6.0 / (in + out));
            for (int i = 0; i < out; ++i) {
                Rng rng(seed, stream * 128 + uint64_t(l), uint64_t(i));
                for (int j = 0; j < in; ++j) W(i, j) = limit * (2.0 * rng.uniformDouble() - 1.0);
                b(i) = 0.0;
            }
        }
    }
    return p;
}

// ---- scaling ------------------------------------------------------------------------------------

MinMaxScaler MinMaxScaler::fit(const Eigen::Ref<const MatX<float>>& data) {
    MinMaxScaler s = identity(data.rows());
    if (data.cols() == 0) return s;
    for (Eigen::Index r = 0; r < data.rows(); ++r) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (Eigen::Index c = 0; c < data.cols(); ++c) {
            const double v = data(r, c);
            if (!std::isfinite(v)) continue;  // NaN/Inf records are rejected upstream; never let them set ranges
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
        if (!(lo <= hi)) continue;  // no finite value: identity
        const double range = hi - lo;
        const double scale = 2.0 / range;
        // A range within float rounding of the values is noise, not signal: the fixed coordinate of
        // a flat wall varies by ~1e-7 through hit-point rounding, and stretching that to [-1, 1]
        // made the networks learn speckle. 1e-5 relative is ~100 float ulps.
        const double magnitude = std::max(std::fabs(lo), std::fabs(hi));
        if (range > 1e-5 * magnitude && std::isfinite(scale)) {
            s.offset(r) = 0.5 * (lo + hi);
            s.scale(r) = scale;
        } else {
            s.offset(r) = lo;  // constant feature: maps to exactly 0
            s.scale(r) = 1.0;
        }
    }
    return s;
}

MinMaxScaler MinMaxScaler::identity(Eigen::Index features) {
    MinMaxScaler s;
    s.offset = VecX<double>::Zero(features);
    s.scale = VecX<double>::Ones(features);
    return s;
}

template <typename S>
void MinMaxScaler::apply(MatX<S>& m) const {
    const VecX<S> o = offset.cast<S>(), k = scale.cast<S>();
    m = ((m.colwise() - o).array().colwise() * k.array()).matrix();
}

template <typename S>
void MinMaxScaler::invert(MatX<S>& m) const {
    const VecX<S> o = offset.cast<S>(), k = scale.cast<S>();
    m = ((m.array().colwise() / k.array()).matrix().colwise() + o);
}

template void MinMaxScaler::apply<float>(MatX<float>&) const;
template void MinMaxScaler::apply<double>(MatX<double>&) const;
template void MinMaxScaler::invert<float>(MatX<float>&) const;
template void MinMaxScaler::invert<double>(MatX<double>&) const;

// ---- passes -------------------------------------------------------------------------------------

namespace {

template <typename S>
using ConstMap = Eigen::Map<const MatX<S>>;

/// f'(z) expressed through the activation a = f(z), which is what the forward pass kept.
template <typename S>
void multiplyByDerivative(Activation act, const MatX<S>& a, MatX<S>& d) {
    if (act == Activation::Tanh)
        d.array() *= S(1) - a.array().square();
    else
        d.array() *= (a.array() > S(0)).template cast<S>();
}

#ifdef RRF_MLP_ISA
/// The arch's layers as the instruction-set passes take them (nn/mlp_isa.h).
struct IsaLayers {
    std::vector<int> inputs, outputs;
    std::vector<std::ptrdiff_t> weight, bias;
    mlp_isa::Layers layers;

    explicit IsaLayers(const MlpArch& arch) {
        for (int l = 0; l < arch.numLayers(); ++l) {
            inputs.push_back(arch.layerInputs(l));
            outputs.push_back(arch.layerOutputs(l));
            weight.push_back(arch.weightOffset(l));
            bias.push_back(arch.biasOffset(l));
        }
        layers = {arch.numLayers(), inputs.data(), outputs.data(), weight.data(), bias.data(),
                  arch.activation == Activation::Tanh ? 1 : 0};
    }
};
#endif

}  // namespace

template <typename S>
void mlpForward(const MlpArch& arch, const S* params, const Eigen::Ref<const MatX<S>>& x,
                std::vector<MatX<S>>& acts) {
    const int L = arch.numLayers();
    acts.resize(size_t(L));
#ifdef RRF_MLP_ISA
    if (const MlpKernel k = mlpKernel(); k != MlpKernel::Portable) {
        const IsaLayers net(arch);
        std::vector<S*> a(static_cast<size_t>(L));
        for (int l = 0; l < L; ++l) {
            acts[size_t(l)].resize(arch.layerOutputs(l), x.cols());
            a[size_t(l)] = acts[size_t(l)].data();
        }
        if (k == MlpKernel::Avx512)
            mlp_isa::avx512::forward(net.layers, params, x.data(), x.outerStride(), x.cols(), a.data());
        else
            mlp_isa::avx2::forward(net.layers, params, x.data(), x.outerStride(), x.cols(), a.data());
        return;
    }
#endif
    for (int l = 0; l < L; ++l) {
        const int in = arch.layerInputs(l), out = arch.layerOutputs(l);
        ConstMap<S> W(params + arch.weightOffset(l), out, in);
        Eigen::Map<const VecX<S>> b(params + arch.biasOffset(l), out);
        MatX<S>& z = acts[size_t(l)];
        z.resize(out, x.cols());
        if (l == 0)
            z.noalias() = W * x;
        else
            z.noalias() = W * acts[size_t(l - 1)];
        z.colwise() += b;
        if (l + 1 < L) {
            if (arch.activation == Activation::Tanh)
                z.array() = z.array().tanh();
            else
                z.array() = z.array().max(S(0));
        }
    }
}

template <typename S>
void mlpBackward(const MlpArch& arch, const S* params, const Eigen::Ref<const MatX<S>>& x,
                 const std::vector<MatX<S>>& acts, const MatX<S>& dOut, std::vector<MatX<S>>& deltas,
                 S* grad, MatX<S>* dInputs) {
    const int L = arch.numLayers();
    deltas.resize(size_t(L));
    deltas[size_t(L - 1)] = dOut;
#ifdef RRF_MLP_ISA
    if (const MlpKernel k = mlpKernel(); k != MlpKernel::Portable) {
        const IsaLayers net(arch);
        std::vector<const S*> a(static_cast<size_t>(L));
        std::vector<S*> d(static_cast<size_t>(L));
        for (int l = 0; l < L; ++l) {
            if (l + 1 < L) deltas[size_t(l)].resize(arch.layerOutputs(l), x.cols());
            a[size_t(l)] = acts[size_t(l)].data();
            d[size_t(l)] = deltas[size_t(l)].data();
        }
        if (dInputs) dInputs->resize(arch.inputs, x.cols());
        S* di = dInputs ? dInputs->data() : nullptr;
        if (k == MlpKernel::Avx512)
            mlp_isa::avx512::backward(net.layers, params, x.data(), x.outerStride(), x.cols(), a.data(), d.data(), grad, di);
        else
            mlp_isa::avx2::backward(net.layers, params, x.data(), x.outerStride(), x.cols(), a.data(), d.data(), grad, di);
        return;
    }
#endif
    for (int l = L - 1; l >= 0; --l) {
        const int in = arch.layerInputs(l), out = arch.layerOutputs(l);
        const MatX<S>& d = deltas[size_t(l)];
        Eigen::Map<MatX<S>> gW(grad + arch.weightOffset(l), out, in);
        Eigen::Map<VecX<S>> gb(grad + arch.biasOffset(l), out);
        if (l == 0)
            gW.noalias() = d * x.transpose();
        else
            gW.noalias() = d * acts[size_t(l - 1)].transpose();
        // A GEMV with a ones vector: rowwise().sum() on a column-major matrix walks it with a stride.
        gb.noalias() = d * VecX<S>::Ones(d.cols());
        if (l > 0) {
            ConstMap<S> W(params + arch.weightOffset(l), out, in);
            MatX<S>& prev = deltas[size_t(l - 1)];
            prev.resize(in, x.cols());
            prev.noalias() = W.transpose() * d;
            multiplyByDerivative(arch.activation, acts[size_t(l - 1)], prev);
        } else if (dInputs) {
            ConstMap<S> W(params + arch.weightOffset(0), out, in);
            dInputs->resize(in, x.cols());
            dInputs->noalias() = W.transpose() * d;  // the input layer has no nonlinearity
        }
    }
}

template <typename S>
void mlpJacobianT(const MlpArch& arch, const S* params, const Eigen::Ref<const MatX<S>>& x,
                  const std::vector<MatX<S>>& acts, std::vector<MatX<S>>& deltas, MatX<S>& jt) {
    const int L = arch.numLayers();
    const Eigen::Index N = x.cols(), K = arch.outputs;
    jt.resize(arch.numParams(), N * K);
    deltas.resize(size_t(L));
    for (Eigen::Index k = 0; k < K; ++k) {
        // The output layer is linear, so ∂out_k/∂z_{L-1} is the unit vector e_k for every sample.
        MatX<S>& top = deltas[size_t(L - 1)];
        top.setZero(K, N);
        top.row(k).setOnes();
        for (int l = L - 1; l >= 0; --l) {
            const int in = arch.layerInputs(l), out = arch.layerOutputs(l);
            const MatX<S>& d = deltas[size_t(l)];
            const auto& a = l == 0 ? x : Eigen::Ref<const MatX<S>>(acts[size_t(l - 1)]);
            const Eigen::Index wo = arch.weightOffset(l), bo = arch.biasOffset(l);
            for (Eigen::Index n = 0; n < N; ++n) {
                S* col = jt.col(k * N + n).data();
                // ∂z_l/∂W_l(i,j) = a_j: the row of J for W_l is the outer product d·aᵀ in W's layout.
                Eigen::Map<MatX<S>>(col + wo, out, in).noalias() = d.col(n) * a.col(n).transpose();
                Eigen::Map<VecX<S>>(col + bo, out) = d.col(n);
            }
            if (l > 0) {
                ConstMap<S> W(params + wo, out, in);
                MatX<S>& prev = deltas[size_t(l - 1)];
                prev.resize(in, N);
                prev.noalias() = W.transpose() * d;
                multiplyByDerivative(arch.activation, acts[size_t(l - 1)], prev);
            }
        }
    }
}

#define RRF_INSTANTIATE_MLP(S)                                                                           \
    template void mlpForward<S>(const MlpArch&, const S*, const Eigen::Ref<const MatX<S>>&,              \
                                std::vector<MatX<S>>&);                                                  \
    template void mlpBackward<S>(const MlpArch&, const S*, const Eigen::Ref<const MatX<S>>&,             \
                                 const std::vector<MatX<S>>&, const MatX<S>&, std::vector<MatX<S>>&, S*, \
                                 MatX<S>*);                                                              \
    template void mlpJacobianT<S>(const MlpArch&, const S*, const Eigen::Ref<const MatX<S>>&,            \
                                  const std::vector<MatX<S>>&, std::vector<MatX<S>>&, MatX<S>&);

RRF_INSTANTIATE_MLP(float)
RRF_INSTANTIATE_MLP(double)

}  // namespace rrf
