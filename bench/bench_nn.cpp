// bench_nn: throughput of the network code against this machine's measured Eigen GEMM rate.
//
//   bench_nn [--quick]
//
// Rows: Eigen float/double GEMM of every kernel the CPU supports (nn/mlp_kernel.h; the fastest is the
// machine's GEMM, the yardstick), one Levenberg–Marquardt epoch against the 3·N·P² flop estimate,
// Adam training, the dense Adam step alone and batched inference for the 20-10, 32-32-32 and
// 64-64-64 networks on every kernel,
// and encoded networks (issue 16: hash grid, frequency and one-blob inputs into 64-64-64 ReLU):
// their forward and forward+backward passes on 1024-sample batches, with the encoding's share of the
// time in a second table.
// Each row's rate is also given as a fraction of the float GEMM of the kernel it ran on, measured in
// the same run ("of own GEMM"): how near that instruction set's peak the passes come.
// Targets (issue 4): Adam and inference ≥ 30 % of the machine's float GEMM rate on one core, LM epoch
// ≤ 2× the estimate at that rate. Every figure is the fastest of several repetitions (the machine is shared).
// Everything runs on synthetic data; no files are read or written.
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "bench/bench_args.h"
#include "core/nn/adam_step.h"
#include "core/nn/encoding.h"
#include "core/nn/encoding_json.h"
#include "core/nn/mlp_kernel.h"
#include "core/nn/model.h"
#include "core/util/json_reader.h"
#include "core/util/rng.h"

using namespace rrf;

namespace bench_nn {

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// GEMM rate of kernel `k`'s build of Eigen (nn/mlp_kernel.h): the yardstick for that instruction set.
template <typename S>
double gemmGflops(MlpKernel k, int n, double minSeconds) {
    MatX<S> a = MatX<S>::Random(n, n), b = MatX<S>::Random(n, n), c(n, n);
    mlpKernelGemm(k, n, a.data(), b.data(), c.data());  // warm-up
    double best = 1e30;
    const double t0 = now();
    do {
        const double t1 = now();
        mlpKernelGemm(k, n, a.data(), b.data(), c.data());
        best = std::min(best, now() - t1);
    } while (now() - t0 < minSeconds);
    if (c(0, 0) == S(12345)) std::printf(" ");  // keep the product observable
    return 2.0 * n * n * double(n) / best / 1e9;
}

MlpArch arch(std::vector<int> hidden, int inputs = 16) {
    MlpArch a;
    a.inputs = inputs;
    a.hidden = std::move(hidden);
    a.outputs = 3;
    return a;
}

/// Normalised synthetic data: smooth targets of uniform inputs.
TrainingData syntheticData(const MlpArch& a, Eigen::Index n) {
    TrainingData d;
    d.xTrain.resize(a.inputs, n);
    d.yTrain.resize(a.outputs, n);
    for (Eigen::Index c = 0; c < n; ++c) {
        Rng rng(1, uint64_t(c));
        for (int r = 0; r < a.inputs; ++r) d.xTrain(r, c) = 2.f * rng.uniform() - 1.f;
        for (int k = 0; k < a.outputs; ++k)
            d.yTrain(k, c) = std::sin(2.f * d.xTrain(k, c) + d.xTrain(k + 3, c)) * 0.8f;
    }
    return d;
}

/// Shortest epoch of a run: the machine is shared, and the minimum is the least disturbed figure.
double fastestEpoch(const TrainResult& r) {
    double best = 1e30;
    for (size_t i = 1; i < r.history.size(); ++i)
        best = std::min(best, r.history[i].seconds - r.history[i - 1].seconds);
    return best;
}

/// Flops of one Adam sample: forward 2·Σ in·out, weight gradients 2·Σ in·out, input deltas of all but
/// the first layer 2·Σ_{l>0} in·out.
double adamFlopsPerSample(const MlpArch& a) {
    return 6.0 * a.macsPerSample() - 2.0 * double(a.layerInputs(0)) * a.layerOutputs(0);
}

/// One table row. `kind` selects the target: 0 none, 1 ≥ 30 % of GEMM, 2 LM (≤ 2× the estimate).
struct Row {
    std::string what, config;
    double value;
    std::string unit;
    double gflops;
    int kind;
    double estimateFlops = 0;  // LM: 3·N·P²
    MlpKernel kernel = MlpKernel::Portable;  // whose passes ran: 'of own GEMM' divides by its GEMM
};

std::vector<Row> g_rows;
double g_gemmF = 0, g_gemmD = 0;  // the machine's: the fastest kernel's GEMM
std::vector<double> g_kernelGemmF(3, 0.0), g_kernelGemmD(3, 0.0);
double g_minT = 1.0;

/// Samples the float GEMM rate of the kernel in use again. The machine is shared and its load changes
/// by 2× within a minute, so each yardstick is the best rate seen over the whole run, sampled between
/// measurements; the machine's GEMM is the fastest kernel's.
void sampleYardstick() {
    double& k = g_kernelGemmF[size_t(mlpKernel())];
    k = std::max(k, gemmGflops<float>(mlpKernel(), 1024, 0.25 * g_minT));
    g_gemmF = std::max(g_gemmF, k);
}

/// Time share of the encoding inside an encoded network's passes (printed under the main table).
struct EncodingShare {
    std::string network, encoding;
    double forwardShare, trainShare;
};
std::vector<EncodingShare> g_shares;

/// Fastest time of `fn` over repetitions filling at least `minSeconds`.
template <typename Fn>
double fastest(Fn&& fn, double minSeconds) {
    fn();  // warm-up (allocations)
    double best = 1e30;
    const double t0 = now();
    do {
        const double t1 = now();
        fn();
        best = std::min(best, now() - t1);
    } while (now() - t0 < minSeconds);
    return best;
}

/// One encoded network: its encoding over the 16 record inputs and the MLP after it.
struct EncodedNetwork {
    std::string label;  // short, for the table's configuration column
    InputEncoding encoding;
    MlpArch arch;
};

EncodedNetwork encodedNetwork(const std::string& label, const char* encodingJson, std::vector<int> hidden) {
    const nlohmann::json j = nlohmann::json::parse(encodingJson);
    EncodedNetwork e;
    e.encoding = inputEncodingFromJson(JsonReader(j, "bench_nn", ""), 16);
    e.arch = arch(std::move(hidden), e.encoding.outputs());
    e.arch.activation = Activation::Relu;
    e.label = label + " + " + e.arch.describe().substr(0, e.arch.describe().find(' '));
    return e;
}

/// Forward (encoding + MLP) and forward+backward (MLP backward, ∂loss/∂features through W_0ᵀ, the
/// encoding's parameter gradients with touched indices, as Adam on an encoded network needs) on a
/// batch of `batch` samples. GFLOP/s counts the MLP's multiply-adds only (2·Σ in·out forward, 4·Σ
/// in·out backward: weight gradients and input deltas of every layer), so the encoding's cost shows
/// as a lower rate than the plain network's.
void benchEncoded(const EncodedNetwork& e, int batch) {
    const MlpArch& a = e.arch;
    const VecX<float> w = initialParams(a, 1).cast<float>();
    const VecX<float> pe = e.encoding.initialParams(1, 0).cast<float>();
    MatX<float> x(16, batch);
    for (Eigen::Index c = 0; c < batch; ++c) {
        Rng rng(3, uint64_t(c));
        for (int r = 0; r < 16; ++r) x(r, c) = 2.f * rng.uniform() - 1.f;
    }
    MatX<float> features, dFeatures, dOut;
    std::vector<MatX<float>> acts, deltas;
    VecX<float> grad(a.numParams());
    VecX<float> gradEnc = VecX<float>::Zero(Eigen::Index(e.encoding.numParams()));
    std::vector<int64_t> touched;
    const Eigen::Map<const MatX<float>> W0(w.data() + a.weightOffset(0), a.layerOutputs(0), a.layerInputs(0));

    auto encodeForward = [&] { e.encoding.forward(pe.data(), x, features); };
    auto encodeBackward = [&] {
        touched.clear();
        e.encoding.backwardParams(pe.data(), x, dFeatures, gradEnc.data(), &touched);
    };
    auto forward = [&] {
        encodeForward();
        mlpForward<float>(a, w.data(), features, acts);
    };
    auto train = [&] {
        forward();
        dOut = acts.back();
        mlpBackward<float>(a, w.data(), features, acts, dOut, deltas, grad.data());
        dFeatures.noalias() = W0.transpose() * deltas[0];
        encodeBackward();
    };
    const double tForward = fastest(forward, g_minT), tTrain = fastest(train, g_minT);
    const double tEncForward = fastest(encodeForward, 0.5 * g_minT);
    train();  // dFeatures of this batch for the encoding-only backward
    const double tEncBackward = fastest(encodeBackward, 0.5 * g_minT);

    char cfgText[96];
    std::snprintf(cfgText, sizeof cfgText, "%s B=%d", e.label.c_str(), batch);
    g_rows.push_back({"Encoded forward", cfgText, batch / tForward, "samples/s",
                      batch * 2.0 * a.macsPerSample() / tForward / 1e9, 1, 0, mlpKernel()});
    g_rows.push_back({"Encoded fwd+bwd", cfgText, batch / tTrain, "samples/s",
                      batch * 6.0 * a.macsPerSample() / tTrain / 1e9, 1, 0, mlpKernel()});
    g_shares.push_back({e.label, e.encoding.describe(), tEncForward / tForward, (tEncForward + tEncBackward) / tTrain});
    sampleYardstick();
}

void printTable() {
    std::printf("\n| %-24s | %-42s | %22s | %8s | %8s | %11s | %-26s |\n", "measurement", "configuration", "result",
                "GFLOP/s", "of GEMM", "of own GEMM", "target");
    std::printf("|%s|%s|%s|%s|%s|%s|%s|\n", std::string(26, '-').c_str(), std::string(44, '-').c_str(),
                std::string(24, '-').c_str(), std::string(10, '-').c_str(), std::string(10, '-').c_str(),
                std::string(13, '-').c_str(), std::string(28, '-').c_str());
    for (const Row& r : g_rows) {
        char verdict[96] = "";
        if (r.kind == 1) {
            std::snprintf(verdict, sizeof verdict, ">= 30%% of GEMM: %s", r.gflops >= 0.3 * g_gemmF ? "ok" : "MISS");
        } else if (r.kind == 2) {
            // LM's JᵀJ runs on the portable build (its Jacobian is not dispatched): judged against that
            // build's float GEMM; the double-rate figure says how close the SYRK gets to its own peak.
            const double gemmF = g_kernelGemmF[size_t(MlpKernel::Portable)], gemmD = g_kernelGemmD[size_t(MlpKernel::Portable)];
            const double est = r.estimateFlops / (gemmF * 1e9);
            std::snprintf(verdict, sizeof verdict, "%.2fx est. %.3f s: %s (%.2fx at f64 rate)", r.value / est, est,
                          r.value <= 2 * est ? "ok" : "MISS", r.value / (r.estimateFlops / (gemmD * 1e9)));
        }
        // The same kernel's float GEMM (double rows: its double GEMM), best seen over this run.
        const bool doubleGemm = r.what == "Eigen GEMM double";
        const double own = (doubleGemm ? g_kernelGemmD : g_kernelGemmF)[size_t(r.kernel)];
        std::printf("| %-24s | %-42s | %12.4g %-9s | %8.2f | %6.0f %% | %9.0f %% | %-26s |\n", r.what.c_str(),
                    r.config.c_str(), r.value, r.unit.c_str(), r.gflops, 100.0 * r.gflops / g_gemmF,
                    100.0 * r.gflops / own, verdict);
    }
}


int main(int argc, char** argv) {
    bool quick = false;
    CLI::App app{"Network throughput (LM, Adam, inference) against this machine's Eigen GEMM rate", "bench_nn"};
    app.add_flag("--quick", quick, "shorter measurements, less data");
    bench::parseArgs(app, argc, argv);
    g_minT = quick ? 0.3 : 1.0;
    const int cores = tbb::info::default_concurrency();

    const MlpKernel chosen = mlpKernel();
    std::printf("bench_nn: %d hardware threads, Eigen %d.%d.%d, portable build SIMD %s; kernels:", cores,
                EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION, Eigen::SimdInstructionSetsInUse());
    for (MlpKernel k : supportedMlpKernels())
        std::printf(" %s%s", mlpKernelName(k), k == chosen ? " (chosen)" : "");
    std::printf("\n");
    // Every kernel's GEMM first: the machine's GEMM (the fastest) is the yardstick of every row.
    for (MlpKernel k : supportedMlpKernels()) {
        setMlpKernel(k);
        sampleYardstick();
        g_kernelGemmD[size_t(k)] = gemmGflops<double>(k, 1024, g_minT);
        g_gemmD = std::max(g_gemmD, g_kernelGemmD[size_t(k)]);
    }
    setMlpKernel(chosen);

    // ---- Levenberg–Marquardt: one epoch at the default max_samples ------------------------------
    {
        const MlpArch a = arch({20, 10});
        const Eigen::Index n = 20000;
        const TrainingData d = syntheticData(a, n);
        LevenbergMarquardtConfig cfg;
        cfg.maxEpochs = quick ? 2 : 4;
        for (int threads : {1, cores}) {
            tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
            VecX<double> w = initialParams(a, 1);
            const TrainResult r = trainLevenbergMarquardt(a, cfg, d, w);
            // Epoch 0 is only the initial SSE; the per-epoch cost is the mean of the later epochs.
            const double perEpoch = fastestEpoch(r);
            const double P = double(a.numParams());
            const double flops = 3.0 * double(n) * P * P;
            char cfgText[64];
            std::snprintf(cfgText, sizeof cfgText, "%s N=%ld P=%.0f %dT", a.describe().c_str(), long(n), P, threads);
            // LM's Jacobian and JᵀJ, most of its time, are not dispatched (nn/mlp_kernel.h).
            g_rows.push_back({"LM epoch", cfgText, perEpoch, "s/epoch", flops / perEpoch / 1e9, 2, flops, MlpKernel::Portable});
            sampleYardstick();
        }
    }

    // ---- Adam training and inference --------------------------------------------------------------
    // Every supported kernel, on the default network, the best preset's and a wide one.
    for (MlpKernel kernel : supportedMlpKernels())
    for (const MlpArch& a : {arch({20, 10}), arch({32, 32, 32}), arch({64, 64, 64})}) {
        setMlpKernel(kernel);
        const Eigen::Index n = quick ? 50000 : 200000;
        TrainingData d = syntheticData(a, n);
        for (int batch : {256, 1024}) {
            AdamConfig cfg;
            cfg.maxEpochs = quick ? 2 : 4;
            cfg.batchSize = batch;
            cfg.patience = 0;
            VecX<double> w = initialParams(a, 1);
            const TrainResult r = trainAdam(a, cfg, d, MinMaxScaler::identity(3), w);
            const double perEpoch = fastestEpoch(r);
            const double sps = double(n) / perEpoch;
            const double gf = sps * adamFlopsPerSample(a) / 1e9;
            char cfgText[64];
            std::snprintf(cfgText, sizeof cfgText, "%s B=%d 1T %s", a.describe().c_str(), batch, mlpKernelName(kernel));
            g_rows.push_back({"Adam training", cfgText, sps, "samples/s", gf, 1, 0, kernel});
            sampleYardstick();
        }
        {
            // The dense Adam step alone (nn/adam_step.h): its share of a batch's time.
            const Eigen::Index P = a.numParams();
            const VecX<float> g = VecX<float>::Random(P), mask = VecX<float>::Ones(P);
            VecX<float> w = VecX<float>::Random(P), mo = VecX<float>::Zero(P), vo = VecX<float>::Zero(P);
            const AdamStepParams p{0.9f, 0.999f, 0.5f, 0.1f, 1e-6f, 1e-8f, 0.f};
            const int reps = 64;
            const double t = fastest([&] { for (int r = 0; r < reps; ++r) adamStep(p, g, mask, w, mo, vo); }, 0.2 * g_minT) / reps;
            char cfgText[64];
            std::snprintf(cfgText, sizeof cfgText, "P=%ld (%s) %s", long(P), a.describe().c_str(), mlpKernelName(kernel));
            g_rows.push_back({"Adam step", cfgText, t * 1e6, "us/step", 0, 0, 0, kernel});
        }
        NetworkModel m;
        m.arch = a;
        m.params = initialParams(a, 2);
        m.inputScaler = MinMaxScaler::identity(a.inputs);
        m.outputScaler = MinMaxScaler::identity(3);
        MatX<float> out = m.predict(d.xTrain.leftCols(4096));  // warm-up
        double best = 1e30;
        const double t0 = now();
        do {
            const double t1 = now();
            out = m.predict(d.xTrain);
            best = std::min(best, now() - t1);
        } while (now() - t0 < g_minT);
        const double sps = double(n) / best;
        const double gf = sps * 2.0 * a.macsPerSample() / 1e9;
        char cfgText[64];
        std::snprintf(cfgText, sizeof cfgText, "%s 1T %s", a.describe().c_str(), mlpKernelName(kernel));
        g_rows.push_back({"Inference (predict)", cfgText, sps, "samples/s", gf, 1, 0, kernel});
        sampleYardstick();
    }
    setMlpKernel(chosen);
    // ---- encoded networks (issue 16), on the chosen kernel -----------------------------------------
    {
        const EncodedNetwork nets[] = {
            encodedNetwork("hash L16 T2^14 F2", R"([{"type": "hash_grid", "inputs": "position"}])", {64, 64, 64}),
            encodedNetwork("freq K6 on 12 in",
                           R"([{"type": "frequency", "inputs": ["position", "view", "light", "normal"]}])", {64, 64, 64}),
            encodedNetwork("blob B16 on 9 in", R"([{"type": "one_blob", "inputs": ["view", "light", "normal"]}])",
                           {64, 64, 64}),
        };
        for (const EncodedNetwork& e : nets) benchEncoded(e, 1024);
    }
    std::vector<Row> gemms;
    for (MlpKernel k : supportedMlpKernels()) {
        const std::string cfg = std::string("1024^3, 1 core, ") + mlpKernelName(k);
        gemms.push_back({"Eigen GEMM float", cfg + " (best seen)", g_kernelGemmF[size_t(k)], "GFLOP/s",
                         g_kernelGemmF[size_t(k)], 0, 0, k});
        gemms.push_back({"Eigen GEMM double", cfg, g_kernelGemmD[size_t(k)], "GFLOP/s", g_kernelGemmD[size_t(k)], 0, 0, k});
    }
    g_rows.insert(g_rows.begin(), gemms.begin(), gemms.end());
    printTable();
    std::printf("\nGFLOP/s counts useful multiply-adds only (2 flops each); 'of GEMM' is relative to the machine's "
                "float GEMM on one core (the fastest kernel's, %.1f GFLOP/s), 'of own GEMM' to the float GEMM of the "
                "kernel the row ran on, in this run (LM: the portable build's, where its Jacobian and JtJ run); "
                "encoded rows run on the chosen kernel (%s).\n",
                g_gemmF, mlpKernelName(chosen));
    std::printf("Encoded networks: GFLOP/s counts the MLP only (forward 2, forward+backward 6 flops per "
                "multiply-add); the encoding's time is overhead on it:\n\n");
    std::printf("| %-38s | %-48s | %16s | %16s |\n", "network", "encoding", "share of forward", "share of fwd+bwd");
    std::printf("|%s|%s|%s|%s|\n", std::string(40, '-').c_str(), std::string(50, '-').c_str(),
                std::string(18, '-').c_str(), std::string(18, '-').c_str());
    for (const EncodingShare& s : g_shares)
        std::printf("| %-38s | %-48s | %14.0f %% | %14.0f %% |\n", s.network.c_str(), s.encoding.c_str(),
                    100.0 * s.forwardShare, 100.0 * s.trainShare);
    return 0;
}

}  // namespace bench_nn
