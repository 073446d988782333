#pragma once
/// The MLP's forward and backward passes compiled for one wider instruction set (AVX2 + FMA, or
/// AVX-512), behind a plain-pointer interface (issue 28 item 1; docs/design.md §10, "Kernels").
///
/// Each instruction set is one translation unit (mlp_isa_<isa>.cpp, which includes mlp_isa.inl)
/// built with that set's compiler flags and called only after the CPU said it has the set
/// (nn/mlp_kernel.h). Nothing but this header crosses the boundary: no Eigen types, no std
/// containers, only ints, pointers and the POD below. Everything such a unit defines lives in its
/// own namespace (rrf::mlp_isa::<isa>, and Eigen itself renamed rrf_eigen_<isa>), so the linker can
/// never pick one of its inline functions, compiled with wider instructions, for the portable
/// build's callers; the CTest `isa_symbols` checks exactly that on the built library.

#include <cstddef>

namespace rrf::mlp_isa {

/// A network's layers: `count` affine layers, layer l maps inputs[l] to outputs[l] features with
/// W_l (outputs[l] × inputs[l], column-major) at params + weight[l] and b_l at params + bias[l];
/// tanh (or ReLU when `tanh` is 0) after every layer but the last.
struct Layers {
    int count = 0;
    const int* inputs = nullptr;
    const int* outputs = nullptr;
    const std::ptrdiff_t* weight = nullptr;
    const std::ptrdiff_t* bias = nullptr;
    int tanh = 1;
};

/// One dense Adam step's constants (nn/adam_step.h's AdamStepParams).
struct AdamStep {
    float beta1, beta2, correction1, correction2, learningRate, epsilon, weightDecay;
};

/// One instruction set's passes; the meaning is mlpForward / mlpBackward's (nn/mlp.h) on raw
/// buffers. `x` is inputs[0] × n with column stride `xStride`; acts[l] and deltas[l] are
/// outputs[l] × n, contiguous, allocated by the caller; deltas[count − 1] holds ∂loss/∂output on
/// entry and is not changed; `dInputs` (inputs[0] × n) may be null. gemm is c = a · b for n × n
/// column-major matrices with this set's Eigen: the yardstick bench_nn measures the passes against.
/// adamStep is nn/adam_step.h's adamStep on `count` entries.
#define RRF_MLP_ISA_DECLARE(isa)                                                                     \
    namespace isa {                                                                                  \
    void forward(const Layers& net, const float* params, const float* x, std::ptrdiff_t xStride,     \
                 std::ptrdiff_t n, float* const* acts);                                              \
    void forward(const Layers& net, const double* params, const double* x, std::ptrdiff_t xStride,   \
                 std::ptrdiff_t n, double* const* acts);                                             \
    void backward(const Layers& net, const float* params, const float* x, std::ptrdiff_t xStride,    \
                  std::ptrdiff_t n, const float* const* acts, float* const* deltas, float* grad,     \
                  float* dInputs);                                                                   \
    void backward(const Layers& net, const double* params, const double* x, std::ptrdiff_t xStride,  \
                  std::ptrdiff_t n, const double* const* acts, double* const* deltas, double* grad,  \
                  double* dInputs);                                                                  \
    void adamStep(const AdamStep& s, std::ptrdiff_t count, const float* grad, const float* decayMask, float* w, \
                  float* m, float* v);                                                               \
    void gemm(std::ptrdiff_t n, const float* a, const float* b, float* c);                          \
    void gemm(std::ptrdiff_t n, const double* a, const double* b, double* c);                       \
    }
RRF_MLP_ISA_DECLARE(avx2)
RRF_MLP_ISA_DECLARE(avx512)
#undef RRF_MLP_ISA_DECLARE

}  // namespace rrf::mlp_isa
