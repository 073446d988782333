// AVX-512 build of the path tracer's lanes (render/path_lanes.h); compiled with -mavx512f -mavx512dq
// -ffp-contract=off (CMakeLists.txt).
#define RRF_ISA avx512
#include "core/render/path_lanes.inl"
