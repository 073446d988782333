#include "core/nn/trainer_config.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/util/json_reader.h"

namespace rrf {

namespace {

using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int64_t kMaxEpochs = 100000000;

}  // namespace

const char* adamLossName(AdamLoss loss) {
    switch (loss) {
    case AdamLoss::RelativeL2: return "relative_l2";
    case AdamLoss::RelativeL2Prediction: return "relative_l2_prediction";
    case AdamLoss::Mse: break;
    }
    return "mse";
}

const char* TrainerConfig::typeName() const {
    return type == TrainerType::Adam ? "adam" : "levenberg_marquardt";
}

TrainerConfig TrainerConfig::fromJson(const json& j, const std::string& file, const std::string& where) {
    return fromJson(JsonReader(j, file, where));
}

TrainerConfig TrainerConfig::fromJson(const JsonReader& r) {
    r.requireObject();
    TrainerConfig c;
    const std::string type = r.choiceOr("type", "levenberg_marquardt", {"levenberg_marquardt", "lm", "adam"});
    if (type == "adam") {
        r.checkKeys({"type", "max_epochs", "batch_size", "learning_rate", "min_learning_rate", "schedule", "step_epochs",
                     "step_gamma", "beta1", "beta2", "epsilon", "weight_decay", "loss", "debias_targets", "patience",
                     "patience_lr_fraction", "error_goal", "max_samples", "seed"});
        c.type = TrainerType::Adam;
        AdamConfig& a = c.adam;
        a.maxEpochs = int(r.integerOr("max_epochs", a.maxEpochs, 0, kMaxEpochs));
        a.batchSize = int(r.integerOr("batch_size", a.batchSize, 1, 1 << 24));
        a.learningRate = r.numberOr("learning_rate", a.learningRate, 0.0, 1e3, true);
        a.minLearningRate = r.numberOr("min_learning_rate", a.minLearningRate, 0.0, 1e3);
        const std::string sched = r.choiceOr("schedule", "cosine", {"constant", "step", "cosine"});
        a.schedule = sched == "constant" ? LrSchedule::Constant : sched == "step" ? LrSchedule::Step : LrSchedule::Cosine;
        a.stepEpochs = int(r.integerOr("step_epochs", a.stepEpochs, 1, kMaxEpochs));
        a.stepGamma = r.numberOr("step_gamma", a.stepGamma, 0.0, 1.0, true);
        a.beta1 = r.numberOr("beta1", a.beta1, 0.0, 1.0 - 1e-12);
        a.beta2 = r.numberOr("beta2", a.beta2, 0.0, 1.0 - 1e-12);
        a.epsilon = r.numberOr("epsilon", a.epsilon, 0.0, 1.0, true);
        a.weightDecay = r.numberOr("weight_decay", a.weightDecay, 0.0, 1.0);
        const std::string loss =
            r.choiceOr("loss", adamLossName(a.loss), {"mse", "relative_l2", "relative_l2_prediction"});
        a.loss = loss == "relative_l2"              ? AdamLoss::RelativeL2
                 : loss == "relative_l2_prediction" ? AdamLoss::RelativeL2Prediction
                                                    : AdamLoss::Mse;
        a.debiasTargets = r.booleanOr("debias_targets", a.debiasTargets);
        a.patience = int(r.integerOr("patience", a.patience, 0, kMaxEpochs));
        a.patienceLrFraction = r.numberOr("patience_lr_fraction", a.patienceLrFraction, 0.0, 1.0, true);
        a.errorGoal = r.numberOr("error_goal", a.errorGoal, 0.0, kInf);
        a.maxSamples = r.integerOr("max_samples", a.maxSamples, 0, INT64_MAX);
        a.seed = r.unsignedOr("seed", a.seed);
    } else {
        r.checkKeys({"type", "max_epochs", "mu", "mu_dec", "mu_inc", "mu_max", "min_grad", "max_fail", "goal",
                     "error_goal", "max_samples", "max_epoch_gflop", "seed"});
        c.type = TrainerType::LevenbergMarquardt;
        LevenbergMarquardtConfig& l = c.lm;
        l.maxEpochs = int(r.integerOr("max_epochs", l.maxEpochs, 0, kMaxEpochs));
        l.mu = r.numberOr("mu", l.mu, 0.0, kInf, true);
        l.muDec = r.numberOr("mu_dec", l.muDec, 0.0, 1.0, true);
        l.muInc = r.numberOr("mu_inc", l.muInc, 1.0, kInf, true);
        l.muMax = r.numberOr("mu_max", l.muMax, 0.0, kInf, true);
        l.minGrad = r.numberOr("min_grad", l.minGrad, 0.0, kInf);
        l.maxFail = int(r.integerOr("max_fail", l.maxFail, 1, kMaxEpochs));
        l.goal = r.numberOr("goal", l.goal, 0.0, kInf);
        l.errorGoal = r.numberOr("error_goal", l.errorGoal, 0.0, kInf);
        l.maxSamples = r.integerOr("max_samples", l.maxSamples, 0, INT64_MAX);
        l.maxEpochGflop = r.numberOr("max_epoch_gflop", l.maxEpochGflop, 0.0, kInf);
        l.seed = r.unsignedOr("seed", l.seed);
        if (l.mu > l.muMax) throw InputError(r.file(), JsonReader::child(r.pointer(), "mu"), "initial mu exceeds mu_max");
    }
    return c;
}

json TrainerConfig::toJson() const {
    if (type == TrainerType::Adam) {
        const AdamConfig& a = adam;
        const char* sched = a.schedule == LrSchedule::Constant ? "constant"
                            : a.schedule == LrSchedule::Step   ? "step"
                                                               : "cosine";
        return json{{"type", "adam"},
                    {"max_epochs", a.maxEpochs},
                    {"batch_size", a.batchSize},
                    {"learning_rate", a.learningRate},
                    {"min_learning_rate", a.minLearningRate},
                    {"schedule", sched},
                    {"step_epochs", a.stepEpochs},
                    {"step_gamma", a.stepGamma},
                    {"beta1", a.beta1},
                    {"beta2", a.beta2},
                    {"epsilon", a.epsilon},
                    {"weight_decay", a.weightDecay},
                    {"loss", adamLossName(a.loss)},
                    {"debias_targets", a.debiasTargets},
                    {"patience", a.patience},
                    {"patience_lr_fraction", a.patienceLrFraction},
                    {"error_goal", a.errorGoal},
                    {"max_samples", a.maxSamples},
                    {"seed", a.seed}};
    }
    const LevenbergMarquardtConfig& l = lm;
    return json{{"type", "levenberg_marquardt"},
                {"max_epochs", l.maxEpochs},
                {"mu", l.mu},
                {"mu_dec", l.muDec},
                {"mu_inc", l.muInc},
                {"mu_max", l.muMax},
                {"min_grad", l.minGrad},
                {"max_fail", l.maxFail},
                {"goal", l.goal},
                {"error_goal", l.errorGoal},
                {"max_samples", l.maxSamples},
                {"max_epoch_gflop", l.maxEpochGflop},
                {"seed", l.seed}};
}

TrainerConfig TrainerConfig::withType(TrainerType t) const {
    TrainerConfig c = *this;
    c.type = t;
    return c;
}

TrainerConfig TrainerConfig::withType(const std::string& name, const std::string& setting) const {
    if (name != "lm" && name != "levenberg_marquardt" && name != "adam")
        throw SettingError(setting, "unknown trainer '" + name + "' (expected lm or adam)");
    return withType(name == "adam" ? TrainerType::Adam : TrainerType::LevenbergMarquardt);
}

}  // namespace rrf
