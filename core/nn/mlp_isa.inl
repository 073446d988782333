// The MLP passes of one instruction set (nn/mlp_isa.h). Included once by each mlp_isa_<isa>.cpp,
// which defines RRF_ISA (its namespace) and is compiled with that set's flags. This file must stay
// the first and only project include of those units: Eigen is renamed before it is included, so
// that every inline function it instantiates here is this unit's own (see mlp_isa.h).
#ifndef RRF_ISA
#error "define RRF_ISA (avx2, avx512) before including mlp_isa.inl"
#endif

#define RRF_ISA_CAT2(a, b) a##b
#define RRF_ISA_CAT(a, b) RRF_ISA_CAT2(a, b)
#define Eigen RRF_ISA_CAT(rrf_eigen_, RRF_ISA)
#include <Eigen/Core>

#include "core/nn/mlp_isa.h"

namespace rrf::mlp_isa::RRF_ISA {

namespace {

using Index = std::ptrdiff_t;
template <typename S> using Mat = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
template <typename S> using Vec = Eigen::Matrix<S, Eigen::Dynamic, 1>;
template <typename S> using Out = Eigen::Map<Mat<S>>;
template <typename S> using In = Eigen::Map<const Mat<S>>;
template <typename S> using Strided = Eigen::Map<const Mat<S>, 0, Eigen::OuterStride<>>;

#include "core/nn/mlp_small.inl"

// The GEMM passes: the same expressions as the portable passes (nn/mlp.cpp), so the two differ by
// rounding only.
template <typename S>
void forwardPass(const Layers& net, const S* params, const S* x, Index xStride, Index n, S* const* acts) {
    for (int l = 0; l < net.count; ++l) {
        const Index in = net.inputs[l], out = net.outputs[l];
        const In<S> W(params + net.weight[l], out, in);
        const Eigen::Map<const Vec<S>> b(params + net.bias[l], out);
        Out<S> z(acts[l], out, n);
        if (l == 0)
            z.noalias() = W * Strided<S>(x, in, n, Eigen::OuterStride<>(xStride));
        else
            z.noalias() = W * In<S>(acts[l - 1], in, n);
        z.colwise() += b;
        if (l + 1 < net.count) {
            if (net.tanh)
                z.array() = z.array().tanh();
            else
                z.array() = z.array().max(S(0));
        }
    }
}

template <typename S>
void backwardPass(const Layers& net, const S* params, const S* x, Index xStride, Index n, const S* const* acts,
                  S* const* deltas, S* grad, S* dInputs) {
    for (int l = net.count - 1; l >= 0; --l) {
        const Index in = net.inputs[l], out = net.outputs[l];
        const In<S> d(deltas[l], out, n);
        Out<S> gW(grad + net.weight[l], out, in);
        Eigen::Map<Vec<S>> gb(grad + net.bias[l], out);
        if (l == 0)
            gW.noalias() = d * Strided<S>(x, in, n, Eigen::OuterStride<>(xStride)).transpose();
        else
            gW.noalias() = d * In<S>(acts[l - 1], in, n).transpose();
        gb.noalias() = d * Vec<S>::Ones(n);
        const In<S> W(params + net.weight[l], out, in);
        if (l > 0) {
            Out<S> prev(deltas[l - 1], in, n);
            prev.noalias() = W.transpose() * d;
            const In<S> a(acts[l - 1], in, n);
            if (net.tanh)
                prev.array() *= S(1) - a.array().square();
            else
                prev.array() *= (a.array() > S(0)).template cast<S>();
        } else if (dInputs) {
            Out<S>(dInputs, in, n).noalias() = W.transpose() * d;
        }
    }
}

template <typename S>
void gemmProduct(Index n, const S* a, const S* b, S* c) {
    Out<S>(c, n, n).noalias() = In<S>(a, n, n) * In<S>(b, n, n);
}

}  // namespace

// Float networks up to small::kMaxWidth wide (backward: kMaxBackwardWidth) take the blocked
// small-layer kernel; wider ones and double (Levenberg–Marquardt, tests) the GEMM.
void forward(const Layers& net, const float* params, const float* x, Index xStride, Index n, float* const* acts) {
    if (small::fits(net)) return small::forward(net, params, x, xStride, n, acts);
    forwardPass(net, params, x, xStride, n, acts);
}
void forward(const Layers& net, const double* params, const double* x, Index xStride, Index n, double* const* acts) {
    forwardPass(net, params, x, xStride, n, acts);
}
void backward(const Layers& net, const float* params, const float* x, Index xStride, Index n, const float* const* acts,
              float* const* deltas, float* grad, float* dInputs) {
    if (small::fits(net, small::kMaxBackwardWidth))
        return small::backward(net, params, x, xStride, n, acts, deltas, grad, dInputs);
    backwardPass(net, params, x, xStride, n, acts, deltas, grad, dInputs);
}
void backward(const Layers& net, const double* params, const double* x, Index xStride, Index n,
              const double* const* acts, double* const* deltas, double* grad, double* dInputs) {
    backwardPass(net, params, x, xStride, n, acts, deltas, grad, dInputs);
}

void adamStep(const AdamStep& s, Index count, const float* grad, const float* decayMask, float* w, float* m,
              float* v) {
    // The expression of the portable step (nn/adam_step.cpp), on this set's packets. Every entry goes
    // through the packet path, the last partial packet through a zero-padded copy: Eigen's own loop
    // would take the entries before the first aligned address one by one (an exact square root
    // instead of the packet's), so a step would depend on where the vectors were allocated.
    using namespace Eigen::internal;
    using P = small::Packet;
    constexpr int kL = small::kLanes;
    const P b1 = pset1<P>(s.beta1), a1 = pset1<P>(1.0f - s.beta1), b2 = pset1<P>(s.beta2),
            a2 = pset1<P>(1.0f - s.beta2), c1 = pset1<P>(s.correction1), c2 = pset1<P>(s.correction2),
            lr = pset1<P>(s.learningRate), eps = pset1<P>(s.epsilon), wd = pset1<P>(s.weightDecay);
    auto step = [&](const float* gp, const float* kp, float* wp, float* mp, float* vp) {
        const P g = ploadu<P>(gp), wi = ploadu<P>(wp);
        const P mi = padd(pmul(b1, ploadu<P>(mp)), pmul(a1, g));
        const P vi = padd(pmul(b2, ploadu<P>(vp)), pmul(a2, pmul(g, g)));
        const P adaptive = pdiv(pdiv(mi, c1), padd(psqrt(pdiv(vi, c2)), eps));
        pstoreu(mp, mi);
        pstoreu(vp, vi);
        pstoreu(wp, psub(wi, pmul(lr, padd(adaptive, pmul(pmul(wd, ploadu<P>(kp)), wi)))));
    };
    Index i = 0;
    for (; i + kL <= count; i += kL) step(grad + i, decayMask + i, w + i, m + i, v + i);
    if (i < count) {
        float g[kL] = {}, k[kL] = {}, wt[kL] = {}, mt[kL] = {}, vt[kL] = {};
        const Index rest = count - i;
        for (Index j = 0; j < rest; ++j) {
            g[j] = grad[i + j];
            k[j] = decayMask[i + j];
            wt[j] = w[i + j];
            mt[j] = m[i + j];
            vt[j] = v[i + j];
        }
        step(g, k, wt, mt, vt);
        for (Index j = 0; j < rest; ++j) {
            w[i + j] = wt[j];
            m[i + j] = mt[j];
            v[i + j] = vt[j];
        }
    }
}

void gemm(Index n, const float* a, const float* b, float* c) { gemmProduct(n, a, b, c); }
void gemm(Index n, const double* a, const double* b, double* c) { gemmProduct(n, a, b, c); }

}  // namespace rrf::mlp_isa::RRF_ISA

#undef Eigen
