#pragma once
/// Which build of the MLP passes runs (issue 28 item 1; docs/design.md §10, "Kernels").
///
/// One binary carries the portable passes (the build's own flags: SSE2 on a Debian-style x86-64
/// build) and the same passes compiled for AVX2 + FMA and for AVX-512 (nn/mlp_isa.h). At first use
/// the fastest one the CPU and the OS support is chosen, unless the environment variable
/// RRF_MLP_KERNEL names one ("portable", "avx2", "avx512"). mlpForward / mlpBackward (nn/mlp.h)
/// dispatch on it; the Jacobian of Levenberg–Marquardt stays portable.
///
/// Kernels differ by rounding (their products sum in other orders), so a model trained with one is
/// reproduced bit for bit by the same kernel only: threads, shards and ranks on one machine agree;
/// runs record the kernel (`settings.kernel`) and the CLI prints it.

#include <string>
#include <vector>

namespace rrf {

enum class MlpKernel { Portable, Avx2, Avx512 };

/// "portable", "avx2", "avx512": the names RRF_MLP_KERNEL takes.
const char* mlpKernelName(MlpKernel k);
/// What a user reads: "portable (SSE2)", "AVX2+FMA", "AVX-512".
std::string mlpKernelDescription(MlpKernel k);
/// True when this CPU (and the OS's saved register state) supports `k`; Portable always.
bool mlpKernelSupported(MlpKernel k);
/// The kernel in use. The first call chooses it (RRF_MLP_KERNEL or the fastest supported) and throws
/// std::invalid_argument naming the variable, its value and what it takes when the variable is set
/// to an unknown or unsupported kernel.
MlpKernel mlpKernel();
/// Uses `k` from now on (benchmarks, tests); throws std::invalid_argument when it is unsupported.
void setMlpKernel(MlpKernel k);

/// Parses a kernel's name (mlpKernelName); throws std::invalid_argument naming `what` (the setting or
/// variable the name came from), the value and the names it takes.
MlpKernel parseMlpKernel(const std::string& name, const std::string& what);
/// All kernels this CPU supports, portable first.
std::vector<MlpKernel> supportedMlpKernels();
/// c = a · b for n × n column-major matrices, computed by kernel `k`'s build of Eigen: the machine's
/// GEMM rate for that instruction set, the yardstick bench_nn measures the passes against.
void mlpKernelGemm(MlpKernel k, long n, const float* a, const float* b, float* c);
void mlpKernelGemm(MlpKernel k, long n, const double* a, const double* b, double* c);

/// Sets a kernel for one scope and restores the previous one (tests).
class ScopedMlpKernel {
public:
    explicit ScopedMlpKernel(MlpKernel k) : previous_(mlpKernel()) { setMlpKernel(k); }
    ~ScopedMlpKernel() { setMlpKernel(previous_); }
    ScopedMlpKernel(const ScopedMlpKernel&) = delete;
    ScopedMlpKernel& operator=(const ScopedMlpKernel&) = delete;

private:
    MlpKernel previous_;
};

}  // namespace rrf
