#include "core/nn/trainer.h"

#include <cmath>
#include <numeric>

#include "core/util/rng.h"

namespace rrf {

namespace {
// Distinct Rng streams for the different random decisions made from one seed.
constexpr uint64_t kSplitStream = 0x53504C4954000000ULL;  // "SPLIT"
}  // namespace

DataSplit splitSamples(size_t n, uint64_t seed, uint64_t stream) {
    std::vector<uint32_t> perm(n);
    std::iota(perm.begin(), perm.end(), 0u);
    Rng rng(seed, kSplitStream, stream);
    for (size_t i = n; i > 1; --i) std::swap(perm[i - 1], perm[rng.uniformInt(uint32_t(i))]);
    // Validation and test are rounded down, so tiny objects keep every sample for training.
    const size_t nVal = size_t(std::floor(0.15 * double(n))), nTest = nVal;
    const size_t nTrain = n - nVal - nTest;
    DataSplit s;
    s.train.assign(perm.begin(), perm.begin() + long(nTrain));
    s.validation.assign(perm.begin() + long(nTrain), perm.begin() + long(nTrain + nVal));
    s.test.assign(perm.begin() + long(nTrain + nVal), perm.end());
    return s;
}

void recordValidation(TrainResult& res, AdamLoss loss, const MinMaxScaler& outputScaler, const TrainingData& data,
                      double goal, const MatX<double>& predNormalised) {
    if (data.xValidation.cols() == 0) return;
    ValidationMonitor monitor(loss, outputScaler, data.yValidation, data.vValidation, goal);
    const ValidationEpoch v = monitor.observe(predNormalised);
    res.validationRelativeRmse = v.relativeRmse;
    res.validationRelativeRmseCorrected = v.relativeRmseCorrected;
    res.validationRelativeNoise = monitor.relativeNoiseFloor();
    res.goalReached = v.goalReached;
}

double networkMse(const MlpArch& arch, const VecX<double>& params, const MatX<float>& x, const MatX<float>& y) {
    if (x.cols() == 0) return std::numeric_limits<double>::quiet_NaN();
    constexpr Eigen::Index kChunk = 4096;
    std::vector<MatX<double>> acts;
    double sse = 0;
    for (Eigen::Index c0 = 0; c0 < x.cols(); c0 += kChunk) {
        const Eigen::Index nc = std::min(kChunk, x.cols() - c0);
        const MatX<double> xc = x.middleCols(c0, nc).cast<double>();
        mlpForward<double>(arch, params.data(), xc, acts);
        sse += (acts.back() - y.middleCols(c0, nc).cast<double>()).squaredNorm();
    }
    return sse / (double(x.cols()) * double(y.rows()));
}

TrainResult trainNetwork(const MlpArch& arch, const TrainerConfig& cfg, const TrainingData& data,
                         const MinMaxScaler& outputScaler, VecX<double>& params, const TrainObserver& observer) {
    if (cfg.type == TrainerType::Adam) return trainAdam(arch, cfg.adam, data, outputScaler, params, observer);
    return trainLevenbergMarquardt(arch, cfg.lm, data, outputScaler, params, observer);
}

int64_t lmSampleCount(const LevenbergMarquardtConfig& cfg, int64_t available, int64_t params, std::string* reason) {
    if (reason) reason->clear();
    int64_t n = available;
    const double flopsPerSample = 3.0 * double(params) * double(params);
    if (cfg.maxEpochGflop > 0) {
        const int64_t budget = std::max<int64_t>(1, int64_t(std::floor(cfg.maxEpochGflop * 1e9 / flopsPerSample)));
        if (budget < n) {
            n = budget;
            if (reason)
                *reason = "levenberg_marquardt: training on a random subsample of " + std::to_string(n) + " of " +
                          std::to_string(available) + " training samples: all of them would cost " +
                          std::to_string(flopsPerSample * double(available) / 1e9) + " GFLOP per epoch (3*N*P^2, P = " +
                          std::to_string(params) + "), above max_epoch_gflop = " + std::to_string(cfg.maxEpochGflop);
        }
    }
    if (cfg.maxSamples > 0 && cfg.maxSamples < n) {
        n = cfg.maxSamples;
        if (reason)
            *reason = "levenberg_marquardt: training on a random subsample of " + std::to_string(n) + " of " +
                      std::to_string(available) + " training samples (max_samples; an epoch costs about 3*N*P^2 = " +
                      std::to_string(flopsPerSample * double(n) / 1e9) + " GFLOP)";
    }
    return n;
}

}  // namespace rrf
