// AVX2 + FMA build of the MLP passes (nn/mlp_isa.h); compiled with -mavx2 -mfma (CMakeLists.txt).
#define RRF_ISA avx2
#include "core/nn/mlp_isa.inl"
