// AVX-512 build of the MLP passes (nn/mlp_isa.h); compiled with -mavx512f -mavx512dq -mfma (CMakeLists.txt).
#define RRF_ISA avx512
#include "core/nn/mlp_isa.inl"
