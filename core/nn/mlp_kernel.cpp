#include "core/nn/mlp_kernel.h"

#include "core/util/cpu_features.h"

#include <atomic>
#include <cstdlib>
#include <stdexcept>

#include <Eigen/Core>

#include "core/nn/mlp_isa.h"

namespace rrf {

namespace {

constexpr MlpKernel kAll[] = {MlpKernel::Portable, MlpKernel::Avx2, MlpKernel::Avx512};

// Preference when nothing is asked for: the widest set the CPU has. bench_nn measures every kernel
// on the radiance networks' own layer sizes (docs/results.md, "kernels"); where a CPU's 512-bit
// units are slower than its 256-bit ones, RRF_MLP_KERNEL=avx2 says so.
constexpr MlpKernel kPreference[] = {MlpKernel::Avx512, MlpKernel::Avx2, MlpKernel::Portable};

MlpKernel chooseKernel() {
    if (const char* v = std::getenv("RRF_MLP_KERNEL"); v && *v) {
        const MlpKernel k = parseMlpKernel(v, "RRF_MLP_KERNEL");
        if (!mlpKernelSupported(k)) {
            std::string names;
            for (MlpKernel s : supportedMlpKernels()) names += (names.empty() ? "" : ", ") + std::string(mlpKernelName(s));
            throw std::invalid_argument("RRF_MLP_KERNEL=" + std::string(v) + ": this CPU does not support " +
                                        mlpKernelDescription(k) + "; it supports " + names);
        }
        return k;
    }
    for (MlpKernel k : kPreference)
        if (mlpKernelSupported(k)) return k;
    return MlpKernel::Portable;
}

std::atomic<int>& activeKernel() {
    static std::atomic<int> k{-1};
    return k;
}

}  // namespace

MlpKernel parseMlpKernel(const std::string& name, const std::string& what) {
    for (MlpKernel k : kAll)
        if (name == mlpKernelName(k)) return k;
    throw std::invalid_argument(what + "=" + name + ": expected portable, avx2 or avx512");
}

std::vector<MlpKernel> supportedMlpKernels() {
    std::vector<MlpKernel> out;
    for (MlpKernel k : kAll)
        if (mlpKernelSupported(k)) out.push_back(k);
    return out;
}

namespace {
template <typename S>
void kernelGemm(MlpKernel k, long n, const S* a, const S* b, S* c) {
#ifdef RRF_MLP_ISA
    if (k == MlpKernel::Avx2) return mlp_isa::avx2::gemm(n, a, b, c);
    if (k == MlpKernel::Avx512) return mlp_isa::avx512::gemm(n, a, b, c);
#endif
    (void)k;
    using M = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
    Eigen::Map<M>(c, n, n).noalias() = Eigen::Map<const M>(a, n, n) * Eigen::Map<const M>(b, n, n);
}
}  // namespace

void mlpKernelGemm(MlpKernel k, long n, const float* a, const float* b, float* c) {
    if (!mlpKernelSupported(k)) throw std::invalid_argument("mlpKernelGemm: unsupported kernel");
    kernelGemm(k, n, a, b, c);
}
void mlpKernelGemm(MlpKernel k, long n, const double* a, const double* b, double* c) {
    if (!mlpKernelSupported(k)) throw std::invalid_argument("mlpKernelGemm: unsupported kernel");
    kernelGemm(k, n, a, b, c);
}

const char* mlpKernelName(MlpKernel k) {
    switch (k) {
        case MlpKernel::Avx2: return "avx2";
        case MlpKernel::Avx512: return "avx512";
        case MlpKernel::Portable: break;
    }
    return "portable";
}

std::string mlpKernelDescription(MlpKernel k) {
    switch (k) {
        case MlpKernel::Avx2: return "AVX2+FMA";
        case MlpKernel::Avx512: return "AVX-512";
        case MlpKernel::Portable: break;
    }
#if defined(__AVX2__)
    return "portable (built with AVX2)";
#elif defined(__AVX__)
    return "portable (built with AVX)";
#else
    return "portable (SSE2)";
#endif
}

bool mlpKernelSupported(MlpKernel k) {
#ifdef RRF_MLP_ISA
    const CpuFeatures& cpu = cpuFeatures();
    switch (k) {
        case MlpKernel::Avx2: return cpu.avx2 && cpu.fma;
        case MlpKernel::Avx512: return cpu.avx512f && cpu.avx512dq && cpu.fma;
        case MlpKernel::Portable: return true;
    }
    return false;
#else
    return k == MlpKernel::Portable;
#endif
}

MlpKernel mlpKernel() {
    std::atomic<int>& a = activeKernel();
    int k = a.load(std::memory_order_acquire);
    if (k < 0) {
        // Concurrent first calls choose the same kernel; the exchange keeps whichever came first.
        int expected = -1;
        a.compare_exchange_strong(expected, int(chooseKernel()), std::memory_order_acq_rel);
        k = a.load(std::memory_order_acquire);
    }
    return MlpKernel(k);
}

void setMlpKernel(MlpKernel k) {
    if (!mlpKernelSupported(k))
        throw std::invalid_argument(std::string("this CPU does not support the ") + mlpKernelDescription(k) +
                                    " kernel");
    activeKernel().store(int(k), std::memory_order_release);
}

}  // namespace rrf
