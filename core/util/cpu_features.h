#pragma once
/// The instruction-set extensions this CPU runs, for the code that picks a kernel built for one of
/// them (the MLP passes, nn/mlp_kernel.h; the tracer's lanes, render/path_lanes.h). GCC's
/// __builtin_cpu_supports checks the OS's XSAVE state too, so a set is never reported whose
/// registers the OS does not save. x86-64 only; elsewhere nothing is reported.

namespace rrf {

struct CpuFeatures {
    bool avx2 = false, fma = false;
    bool avx512f = false, avx512dq = false;
};

/// This CPU's, asked once.
inline const CpuFeatures& cpuFeatures() {
    static const CpuFeatures features = [] {
        CpuFeatures f;
#if defined(__x86_64__) && defined(__GNUC__)
        f.avx2 = __builtin_cpu_supports("avx2");
        f.fma = __builtin_cpu_supports("fma");
        f.avx512f = __builtin_cpu_supports("avx512f");
        f.avx512dq = __builtin_cpu_supports("avx512dq");
#endif
        return f;
    }();
    return features;
}

}  // namespace rrf
