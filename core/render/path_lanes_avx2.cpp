// AVX2 build of the path tracer's lanes (render/path_lanes.h); compiled with -mavx2
// -ffp-contract=off (CMakeLists.txt).
#define RRF_ISA avx2
#include "core/render/path_lanes.inl"
