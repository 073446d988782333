#include "core/render/path_lanes.h"

#include "core/util/cpu_features.h"

// The lanes give trace()'s bits only where the portable code fuses no multiply-adds either: a build
// whose base flags allow FMA (say -march=x86-64-v3) keeps the portable lockstep.
#if defined(RRF_PATH_LANES) && !defined(__FMA__)
#define RRF_PATH_LANES_RUN 1
#endif

namespace rrf {

namespace path_lanes {
const char* isaName(Isa isa) {
    switch (isa) {
        case Isa::Avx2: return "AVX2 lanes";
        case Isa::Avx512: return "AVX-512 lanes";
        case Isa::None: break;
    }
    return "portable";
}

bool isaSupported(Isa isa) {
#ifdef RRF_PATH_LANES_RUN
    const CpuFeatures& cpu = cpuFeatures();
    switch (isa) {
        case Isa::Avx2: return cpu.avx2;
        case Isa::Avx512: return cpu.avx512f && cpu.avx512dq;
        case Isa::None: return true;
    }
    return false;
#else
    return isa == Isa::None;
#endif
}

Isa bestIsa() {
    if (isaSupported(Isa::Avx512)) return Isa::Avx512;
    if (isaSupported(Isa::Avx2)) return Isa::Avx2;
    return Isa::None;
}

Kernels kernelsOf(Isa isa) {
#ifdef RRF_PATH_LANES
    if (isa == Isa::Avx512) return {&avx512::step, &avx512::start};
    if (isa == Isa::Avx2) return {&avx2::step, &avx2::start};
#endif
    (void)isa;
    return {};
}
}  // namespace path_lanes

}  // namespace rrf
