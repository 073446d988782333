#include "core/nn/block_forward.h"

#include <numeric>

namespace rrf {

namespace {

/// True when W_l (out × in, column-major) has nothing but zeros outside its k diagonal blocks.
template <typename S>
bool blockDiagonal(const S* W, int out, int in, int k) {
    const int bo = out / k, bi = in / k;
    for (int c = 0; c < in; ++c) {
        const int r0 = (c / bi) * bo, r1 = r0 + bo;  // rows of column c's block
        const S* col = W + size_t(c) * size_t(out);
        for (int r = 0; r < r0; ++r)
            if (col[r] != S(0)) return false;
        for (int r = r1; r < out; ++r)
            if (col[r] != S(0)) return false;
    }
    return true;
}

template <typename S>
void activate(const MlpArch& arch, MatX<S>& z) {
    if (arch.activation == Activation::Tanh)
        z.array() = z.array().tanh();
    else
        z.array() = z.array().max(S(0));
}

}  // namespace

template <typename S>
int blockMembers(const MlpArch& arch, const S* params) {
    if (arch.hidden.size() < 2) return 1;
    int g = 0;
    for (int h : arch.hidden) g = std::gcd(g, h);
    for (int k = g; k >= 2; --k) {
        if (g % k != 0) continue;
        bool all = true;
        for (int l = 1; all && l + 1 < arch.numLayers(); ++l)
            all = blockDiagonal(params + arch.weightOffset(l), arch.layerOutputs(l), arch.layerInputs(l), k);
        if (all) return k;
    }
    return 1;
}

template <typename S>
void blockForward(const MlpArch& arch, int members, const S* params, const Eigen::Ref<const MatX<S>>& x,
                  std::vector<MatX<S>>& acts) {
    if (members <= 1) {
        mlpForward<S>(arch, params, x, acts);
        return;
    }
    const int L = arch.numLayers();
    acts.resize(size_t(L));
    for (int l = 0; l < L; ++l) {
        const int in = arch.layerInputs(l), out = arch.layerOutputs(l);
        const Eigen::Map<const MatX<S>> W(params + arch.weightOffset(l), out, in);
        const Eigen::Map<const VecX<S>> b(params + arch.biasOffset(l), out);
        MatX<S>& z = acts[size_t(l)];
        z.resize(out, x.cols());
        if (l == 0) {
            z.noalias() = W * x;
        } else if (l + 1 == L) {
            z.noalias() = W * acts[size_t(l - 1)];
        } else {
            // Member m's units read only member m's units of the layer below.
            const int bo = out / members, bi = in / members;
            const MatX<S>& a = acts[size_t(l - 1)];
            for (int m = 0; m < members; ++m)
                z.middleRows(m * bo, bo).noalias() = W.block(m * bo, m * bi, bo, bi) * a.middleRows(m * bi, bi);
        }
        z.colwise() += b;
        if (l + 1 < L) activate(arch, z);
    }
}

template int blockMembers<float>(const MlpArch&, const float*);
template int blockMembers<double>(const MlpArch&, const double*);
template void blockForward<float>(const MlpArch&, int, const float*, const Eigen::Ref<const MatX<float>>&,
                                  std::vector<MatX<float>>&);
template void blockForward<double>(const MlpArch&, int, const double*, const Eigen::Ref<const MatX<double>>&,
                                   std::vector<MatX<double>>&);

}  // namespace rrf
