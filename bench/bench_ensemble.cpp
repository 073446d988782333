// bench_ensemble: forward passes of merged ensembles (core/nn/ensemble.h), dense against member by
// member (core/nn/block_forward.h), in one run, one thread, float, in the predictor's 2048-sample
// chunks over 65536 samples (a 256x256 frame's worth):
//
//   bench_ensemble [--quick]
//
// Rows: K members of 20-10 (the best preset's four and eight) and of 64-64-64 tanh, each with its
// multiply-adds per sample both ways, samples per second both ways (fastest of several repetitions:
// the machine is shared), the speed-up, and the largest difference of the outputs.
#include <chrono>
#include <cstdio>
#include <vector>

#include <tbb/global_control.h>

#include "bench/bench_args.h"
#include "core/nn/block_forward.h"
#include "core/nn/ensemble.h"

using namespace rrf;

namespace bench_ensemble {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

/// Multiply–adds per sample of the merged network, dense and without the zero blocks.
void macs(const MlpArch& merged, int k, double& dense, double& blocked) {
    dense = blocked = 0;
    for (int l = 0; l < merged.numLayers(); ++l) {
        const double m = double(merged.layerInputs(l)) * double(merged.layerOutputs(l));
        dense += m;
        blocked += (l == 0 || l + 1 == merged.numLayers()) ? m : m / k;
    }
}


int main(int argc, char** argv) {
    bool quick = false;
    CLI::App app{"merged ensembles: dense forward pass against member by member", "bench_ensemble"};
    app.add_flag("--quick", quick, "fewer repetitions");
    bench::parseArgs(app, argc, argv);
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const int reps = quick ? 3 : 10;
    const Eigen::Index n = 65536, chunk = 2048;
    MatX<float> x = MatX<float>::Random(16, n);

    std::printf("bench_ensemble: 1 thread, float, %lld samples in chunks of %lld, fastest of %d\n\n", (long long)n,
                (long long)chunk, reps);
    std::printf("| members x network | MACs/sample dense | member by member | dense Msamples/s | member by member "
                "Msamples/s | speed-up | max |difference| |\n|---|---|---|---|---|---|---|\n");
    struct Case {
        int k;
        std::vector<int> hidden;
    };
    for (const Case& c : {Case{4, {20, 10}}, Case{8, {20, 10}}, Case{4, {64, 64, 64}}}) {
        MlpArch member;
        member.inputs = 16;
        member.hidden = c.hidden;
        member.outputs = 3;
        std::vector<VecX<double>> params;
        for (int m = 0; m < c.k; ++m) params.push_back(initialParams(member, 3 + uint64_t(m), 1));
        const MlpArch merged = ensembleArch(member, c.k);
        const VecX<float> w = mergeEnsemble(member, params).cast<float>();
        const int k = blockMembers(merged, w.data());
        MatX<float> outDense(3, n), outBlock(3, n);
        double best[2] = {1e30, 1e30};
        std::vector<MatX<float>> acts;
        for (int r = 0; r < reps; ++r)
            for (int way = 0; way < 2; ++way) {
                MatX<float>& out = way == 0 ? outDense : outBlock;
                const double t0 = now();
                for (Eigen::Index s = 0; s < n; s += chunk) {
                    const Eigen::Index nc = std::min(chunk, n - s);
                    const Eigen::Ref<const MatX<float>> xs = x.middleCols(s, nc);
                    if (way == 0) mlpForward<float>(merged, w.data(), xs, acts);
                    else blockForward<float>(merged, k, w.data(), xs, acts);
                    out.middleCols(s, nc) = acts.back();
                }
                best[way] = std::min(best[way], now() - t0);
            }
        double md, mb;
        macs(merged, c.k, md, mb);
        std::printf("| %d x %s (found %d) | %.0f | %.0f | %.2f | %.2f | %.2fx | %.2g |\n", c.k, member.describe().c_str(),
                    k, md, mb, 1e-6 * double(n) / best[0], 1e-6 * double(n) / best[1], best[0] / best[1],
                    double((outDense - outBlock).cwiseAbs().maxCoeff()));
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace bench_ensemble
