// Levenberg–Marquardt training with Matlab trainlm semantics (see core/nn/trainer.h).
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/nn/trainer.h"

namespace rrf {

namespace {

// Samples per rank update: 256 samples × 3 outputs = 768 rows of J, deep enough for the SYRK kernel to
// run near the double GEMM rate while the chunk of J stays small (P × 768 doubles ≈ 3.6 MB for P = 600).
constexpr Eigen::Index kChunk = 256;
// Fixed number of partial sums, independent of the thread count, so the reduction order (and every
// bit of the result) is the same on 1 or 64 threads.
constexpr int kMaxBlocks = 8;
// JᵀJ beyond this many parameters needs > 280 MB per copy: Adam is the tool there.
constexpr Eigen::Index kMaxParams = 6000;

struct Block {
    Eigen::Index begin = 0, end = 0;  // sample range
    MatX<double> jtj;                 // lower triangle
    VecX<double> jte;
    double sse = 0;
    std::vector<MatX<double>> acts, deltas;
    MatX<double> jt, residual;
};

/// The training problem on the (sub)sampled training set, in double.
class LmProblem {
public:
    LmProblem(const MlpArch& arch, MatX<double> x, MatX<double> y) : arch_(arch), x_(std::move(x)), y_(std::move(y)) {
        const Eigen::Index n = x_.cols();
        const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
        const Eigen::Index p = arch_.numParams();
        const double bytesPerBlock = double(p) * double(p) * 8.0;
        const int memBlocks = int(std::max(1.0, std::floor(512e6 / bytesPerBlock)));
        const int nb = int(std::max<Eigen::Index>(1, std::min<Eigen::Index>({chunks, kMaxBlocks, memBlocks})));
        blocks_.resize(size_t(nb));
        for (int b = 0; b < nb; ++b) {
            // Block boundaries on chunk multiples, so the SSE pass uses exactly the same GEMM shapes
            // as the Jacobian pass and both give bit-identical errors.
            blocks_[size_t(b)].begin = std::min(n, chunks * b / nb * kChunk);
            blocks_[size_t(b)].end = std::min(n, chunks * (b + 1) / nb * kChunk);
        }
    }

    Eigen::Index samples() const { return x_.cols(); }

    /// JᵀJ (lower triangle), Jᵀe and the SSE at `w`.
    void accumulate(const VecX<double>& w, MatX<double>& jtj, VecX<double>& jte, double& sse) {
        const Eigen::Index p = arch_.numParams();
        tbb::parallel_for(size_t(0), blocks_.size(), [&](size_t bi) {
            Block& b = blocks_[bi];
            b.jtj.setZero(p, p);
            b.jte.setZero(p);
            b.sse = 0;
            for (Eigen::Index c = b.begin; c < b.end; c += kChunk) {
                const Eigen::Index nc = std::min(kChunk, b.end - c);
                const auto xc = x_.middleCols(c, nc);
                mlpForward<double>(arch_, w.data(), xc, b.acts);
                b.residual = (b.acts.back() - y_.middleCols(c, nc)).transpose();  // row k·nc + n order
                b.sse += b.residual.squaredNorm();
                mlpJacobianT<double>(arch_, w.data(), xc, b.acts, b.deltas, b.jt);
                b.jtj.selfadjointView<Eigen::Lower>().rankUpdate(b.jt);
                b.jte.noalias() += b.jt * Eigen::Map<const VecX<double>>(b.residual.data(), b.residual.size());
            }
        });
        jtj = std::move(blocks_[0].jtj);
        jte = std::move(blocks_[0].jte);
        sse = blocks_[0].sse;
        for (size_t bi = 1; bi < blocks_.size(); ++bi) {
            jtj.triangularView<Eigen::Lower>() += blocks_[bi].jtj;
            jte += blocks_[bi].jte;
            sse += blocks_[bi].sse;
        }
    }

    /// SSE at `w`, chunked exactly as accumulate().
    double sse(const VecX<double>& w) {
        tbb::parallel_for(size_t(0), blocks_.size(), [&](size_t bi) {
            Block& b = blocks_[bi];
            b.sse = 0;
            for (Eigen::Index c = b.begin; c < b.end; c += kChunk) {
                const Eigen::Index nc = std::min(kChunk, b.end - c);
                mlpForward<double>(arch_, w.data(), x_.middleCols(c, nc), b.acts);
                b.residual = (b.acts.back() - y_.middleCols(c, nc)).transpose();
                b.sse += b.residual.squaredNorm();
            }
        });
        double s = 0;
        for (const Block& b : blocks_) s += b.sse;
        return s;
    }

private:
    const MlpArch& arch_;
    MatX<double> x_, y_;
    std::vector<Block> blocks_;
};

}  // namespace

TrainResult trainLevenbergMarquardt(const MlpArch& arch, const LevenbergMarquardtConfig& cfg,
                                    const TrainingData& data, VecX<double>& params, const TrainObserver& observer) {
    return trainLevenbergMarquardt(arch, cfg, data, MinMaxScaler::identity(arch.outputs), params, observer);
}

TrainResult trainLevenbergMarquardt(const MlpArch& arch, const LevenbergMarquardtConfig& cfg,
                                    const TrainingData& data, const MinMaxScaler& outputScaler, VecX<double>& params,
                                    const TrainObserver& observer) {
    arch.validate();
    const Eigen::Index P = arch.numParams();
    if (P > kMaxParams)
        throw std::invalid_argument("levenberg_marquardt: the " + arch.describe() + " network has " +
                                    std::to_string(P) + " parameters; JᵀJ would need " +
                                    std::to_string(P * P * 8 / 1000000) + " MB per copy (limit " +
                                    std::to_string(kMaxParams) + " parameters): use the adam trainer");
    if (params.size() != P) throw std::invalid_argument("levenberg_marquardt: parameter vector has the wrong size");
    if (outputScaler.size() != arch.outputs)
        throw std::invalid_argument("levenberg_marquardt: output scaler size mismatch");
    const auto t0 = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };

    TrainResult res;
    res.trainSamples = data.xTrain.cols();
    res.validationSamples = data.xValidation.cols();
    res.testSamples = data.xTest.cols();
    res.errorGoal = cfg.errorGoal;
    auto note = [&](const std::string& m) {
        res.messages.push_back(m);
        if (observer.onMessage) observer.onMessage(m);
    };
    if (data.xTrain.cols() == 0) throw std::invalid_argument("levenberg_marquardt: no training samples");

    // The split is a random permutation, so its first n training columns are a random subset.
    std::string bound;
    const Eigen::Index n = Eigen::Index(lmSampleCount(cfg, data.xTrain.cols(), P, &bound));
    if (!bound.empty()) note(bound);
    res.trainSamplesUsed = n;
    LmProblem problem(arch, data.xTrain.leftCols(n).cast<double>(), data.yTrain.leftCols(n).cast<double>());
    const double count = double(n) * arch.outputs;
    const bool hasVal = data.xValidation.cols() > 0;
    // The validation loss is the normalised MSE (what trainlm compares); the goal is the raw relative RMSE.
    ValidationMonitor monitor(AdamLoss::Mse, outputScaler, data.yValidation, data.vValidation, cfg.errorGoal);
    FailureCounter failures(cfg.maxFail, /*countUnchanged=*/false);
    std::vector<MatX<double>> acts;
    const MatX<double> xVal = data.xValidation.cast<double>();
    auto validate = [&](const VecX<double>& w) {
        if (!hasVal) return ValidationEpoch{};
        mlpForward<double>(arch, w.data(), xVal, acts);
        return monitor.observe(acts.back());
    };
    auto figure = [](const ValidationEpoch& v) {
        return std::isnan(v.relativeRmseCorrected) ? v.relativeRmse : v.relativeRmseCorrected;
    };

    MatX<double> jtj, A;
    VecX<double> jte, dx, trial;
    VecX<double> best = params;
    double mu = cfg.mu;
    bool ldltNoted = false, goalReached = false;

    double sse = problem.sse(params);
    {
        const ValidationEpoch v = validate(params);
        goalReached = v.goalReached;
        EpochRecord r{0, sse / count, v.loss, mu, elapsed()};
        r.validationRelativeRmse = figure(v);
        res.history.push_back(r);
        if (observer.onEpoch) observer.onEpoch(res.history.back());
    }
    for (int epoch = 0;; ++epoch) {
        // Stop tests in trainlm's order (the error goal beside trainlm's goal); the gradient test
        // needs Jᵀe, so JᵀJ is only built when needed.
        const double perf = sse / count;
        if (perf <= cfg.goal) res.stopReason = "performance goal met";
        else if (goalReached) res.stopReason = "error goal reached";
        else if (epoch >= cfg.maxEpochs) res.stopReason = "maximum epoch reached";
        else if (mu > cfg.muMax) res.stopReason = "maximum mu reached";
        else if (hasVal && failures.reached()) res.stopReason = "validation stop";
        else if (observer.cancelled()) {
            res.stopReason = "cancelled";
            res.cancelled = true;
        }
        if (res.stopReason.empty()) {
            problem.accumulate(params, jtj, jte, sse);
            if (jte.norm() < cfg.minGrad) res.stopReason = "minimum gradient reached";
        }
        if (!res.stopReason.empty()) break;

        // Raise μ until a step lowers the training SSE (or μ passes mu_max).
        double stepMu = mu;
        while (mu <= cfg.muMax) {
            A = jtj;
            A.diagonal().array() += mu;
            Eigen::LLT<MatX<double>, Eigen::Lower> llt(A);
            if (llt.info() == Eigen::Success) {
                dx = -llt.solve(jte);
            } else {
                // JᵀJ + μI is positive definite in exact arithmetic; rounding can break that when μ is
                // tiny against a huge diagonal. LDLT still gives a usable step; if not, μ grows.
                if (!ldltNoted) note("levenberg_marquardt: Cholesky failed (JᵀJ + μI not numerically positive definite); using LDLT");
                ldltNoted = true;
                Eigen::LDLT<MatX<double>, Eigen::Lower> ldlt(A);
                dx = -ldlt.solve(jte);
            }
            if (dx.allFinite()) {
                trial = params + dx;
                const double s = problem.sse(trial);
                if (std::isfinite(s) && s < sse) {
                    params.swap(trial);
                    sse = s;
                    stepMu = mu;
                    mu = std::max(mu * cfg.muDec, 1e-20);
                    break;
                }
            }
            mu *= cfg.muInc;
            stepMu = mu;
        }

        const ValidationEpoch v = validate(params);
        if (hasVal) {
            if (v.outcome == ValidationOutcome::Improved) {
                best = params;
                res.bestEpoch = epoch + 1;
            }
            failures.update(v.outcome, 0.0);
            if (v.goalReached) {
                // Weights that meet the goal are kept even if another epoch had a lower MSE.
                goalReached = true;
                monitor.acceptLastAsBest();
                best = params;
                res.bestEpoch = epoch + 1;
            }
        }
        res.epochs = epoch + 1;
        EpochRecord r{epoch + 1, sse / count, v.loss, stepMu, elapsed()};
        r.validationRelativeRmse = figure(v);
        r.failureWithinNoise = v.outcome == ValidationOutcome::FailedWithinNoise;
        res.history.push_back(r);
        if (observer.onEpoch) observer.onEpoch(res.history.back());
    }

    if (hasVal) params = best;
    else res.bestEpoch = res.epochs;
    res.trainLoss = networkMse(arch, params, data.xTrain, data.yTrain);
    res.validationLoss = networkMse(arch, params, data.xValidation, data.yValidation);
    res.testLoss = networkMse(arch, params, data.xTest, data.yTest);
    if (hasVal) {
        mlpForward<double>(arch, params.data(), xVal, acts);
        recordValidation(res, AdamLoss::Mse, outputScaler, data, cfg.errorGoal, acts.back());
    }
    res.seconds = elapsed();
    return res;
}

}  // namespace rrf
