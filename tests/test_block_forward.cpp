// Merged ensembles evaluated member by member (core/nn/block_forward.h) against their definition:
// the mean of the members' own forward passes, and against the dense forward pass of the merged
// network (nn/ensemble.h), to rounding; the block count read from the weights.

#include <gtest/gtest.h>

#include "core/nn/block_forward.h"
#include "core/nn/ensemble.h"
#include "core/nn/model.h"

namespace test_block_forward {

using namespace rrf;

namespace {

MlpArch arch(std::vector<int> hidden, Activation a = Activation::Tanh) {
    MlpArch m;
    m.inputs = 16;
    m.hidden = std::move(hidden);
    m.outputs = 3;
    m.activation = a;
    return m;
}

std::vector<VecX<double>> members(const MlpArch& a, int k) {
    std::vector<VecX<double>> p;
    for (int m = 0; m < k; ++m) p.push_back(initialParams(a, 11 + uint64_t(m), 3));
    return p;
}

MatX<double> inputs(int rows, int cols) {
    MatX<double> x(rows, cols);
    for (int c = 0; c < cols; ++c)
        for (int r = 0; r < rows; ++r) x(r, c) = std::sin(0.37 * r + 1.3 * c);  // in [-1, 1], as scaled inputs
    return x;
}

}  // namespace

TEST(BlockForward, MembersAreReadFromTheWeights) {
    for (int k : {1, 2, 3, 4, 8}) {
        const MlpArch member = arch({20, 10});
        const VecX<double> merged = mergeEnsemble(member, members(member, k));
        EXPECT_EQ(blockMembers(ensembleArch(member, k), merged.data()), k) << k << " members";
    }
    const MlpArch deep = arch({12, 8, 6}, Activation::Relu);
    EXPECT_EQ(blockMembers(ensembleArch(deep, 4), mergeEnsemble(deep, members(deep, 4)).data()), 4);
    const MlpArch one = arch({20});
    EXPECT_EQ(blockMembers(ensembleArch(one, 4), mergeEnsemble(one, members(one, 4)).data()), 1)
        << "one hidden layer: no hidden-to-hidden matrix, nothing to skip";
    const MlpArch plain = arch({40, 20});
    EXPECT_EQ(blockMembers(plain, initialParams(plain, 5, 0).data()), 1) << "a dense network";
}

TEST(BlockForward, EqualsTheMeanOfTheMembersAndTheDensePass) {
    for (const MlpArch& member : {arch({20, 10}), arch({12, 8, 6}, Activation::Relu), arch({64, 64, 64})}) {
        const int k = 4;
        const std::vector<VecX<double>> p = members(member, k);
        const MlpArch ma = ensembleArch(member, k);
        const VecX<double> merged = mergeEnsemble(member, p);
        const MatX<double> x = inputs(member.inputs, 300);
        // The definition: the mean of the members' outputs.
        MatX<double> mean = MatX<double>::Zero(member.outputs, x.cols());
        std::vector<MatX<double>> acts;
        for (const VecX<double>& w : p) {
            mlpForward<double>(member, w.data(), x, acts);
            mean += acts.back() / double(k);
        }
        std::vector<MatX<double>> blocked, dense;
        blockForward<double>(ma, blockMembers(ma, merged.data()), merged.data(), x, blocked);
        mlpForward<double>(ma, merged.data(), x, dense);
        EXPECT_LT((blocked.back() - mean).cwiseAbs().maxCoeff(), 1e-12) << member.describe();
        EXPECT_LT((blocked.back() - dense.back()).cwiseAbs().maxCoeff(), 1e-12) << member.describe();
        // In float, as the predictor runs: the dense pass's values to float rounding.
        const VecX<float> wf = merged.cast<float>();
        const MatX<float> xf = x.cast<float>();
        std::vector<MatX<float>> bf, df;
        blockForward<float>(ma, blockMembers(ma, wf.data()), wf.data(), xf, bf);
        mlpForward<float>(ma, wf.data(), xf, df);
        EXPECT_LT((bf.back() - df.back()).cwiseAbs().maxCoeff(), 1e-5f) << member.describe();
    }
}

TEST(BlockForward, NetworkModelPredictsAnEnsembleMemberByMember) {
    // NetworkModel::predict takes the member-by-member pass for a merged ensemble: it must equal the
    // mean of the member models' predictions (same scalers) to float rounding.
    const MlpArch member = arch({20, 10});
    const std::vector<VecX<double>> p = members(member, 4);
    NetworkModel merged;
    merged.arch = ensembleArch(member, 4);
    merged.params = mergeEnsemble(member, p);
    merged.inputScaler = MinMaxScaler::identity(member.inputs);
    merged.outputScaler = MinMaxScaler::identity(3);
    const MatX<float> x = inputs(member.inputs, 5000).cast<float>();  // more than one inference chunk
    MatX<float> mean = MatX<float>::Zero(3, x.cols());
    for (const VecX<double>& w : p) {
        NetworkModel one = merged;
        one.arch = member;
        one.params = w;
        mean += one.predict(x) / 4.f;
    }
    EXPECT_LT((merged.predict(x) - mean).cwiseAbs().maxCoeff(), 1e-5f);
}

}  // namespace test_block_forward
