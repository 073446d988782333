#include "core/nn/trainer_config_json.h"

#include <cmath>
#include <limits>

#include "core/nn/trainers/registry.h"

namespace rrf {

namespace {

using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int64_t kMaxEpochs = 100000000;

/// Reads the keys every trainer has over `c`'s values.
void readCommon(const JsonReader& r, TrainerCommon& c) {
    c.maxEpochs = int(r.integerOr("max_epochs", c.maxEpochs, 0, kMaxEpochs));
    c.errorGoal = r.numberOr("error_goal", c.errorGoal, 0.0, kInf);
    c.maxSamples = r.integerOr("max_samples", c.maxSamples, 0, INT64_MAX);
    c.seed = r.unsignedOr("seed", c.seed);
}

/// Writes the keys every trainer has into `j` (an object; its keys are sorted when written, so the
/// order of these calls does not show in the file).
void writeCommon(const TrainerCommon& c, json& j) {
    j["max_epochs"] = c.maxEpochs;
    j["error_goal"] = c.errorGoal;
    j["max_samples"] = c.maxSamples;
    j["seed"] = c.seed;
}

}  // namespace

TrainerConfig trainerConfigFromJson(const json& j, const std::string& file, const std::string& where) {
    return trainerConfigFromJson(JsonReader(j, file, where));
}

TrainerConfig trainerConfigFromJson(const JsonReader& r) {
    r.requireObject();
    TrainerConfig c;
    // A trainer object without "type" is Levenberg–Marquardt (the registry's first row).
    const TrainerTypeInfo& info =
        *findTrainerType(r.choiceOr("type", trainerTypes().front().name, trainerTypeNames()));
    r.checkKeys(info.keys);
    c.type = info.type;
    readCommon(r, c.common());
    if (c.type == TrainerType::Adam) {
        AdamConfig& a = c.adam;
        a.batchSize = int(r.integerOr("batch_size", a.batchSize, 1, 1 << 24));
        a.learningRate = r.numberOr("learning_rate", a.learningRate, 0.0, 1e3, true);
        a.minLearningRate = r.numberOr("min_learning_rate", a.minLearningRate, 0.0, 1e3);
        a.schedule = valueNamed(lrSchedules(), r.choiceOr("schedule", nameOf(lrSchedules(), a.schedule),
                                                                 valueNames(lrSchedules())));
        a.stepEpochs = int(r.integerOr("step_epochs", a.stepEpochs, 1, kMaxEpochs));
        a.stepGamma = r.numberOr("step_gamma", a.stepGamma, 0.0, 1.0, true);
        a.beta1 = r.numberOr("beta1", a.beta1, 0.0, 1.0 - 1e-12);
        a.beta2 = r.numberOr("beta2", a.beta2, 0.0, 1.0 - 1e-12);
        a.epsilon = r.numberOr("epsilon", a.epsilon, 0.0, 1.0, true);
        a.weightDecay = r.numberOr("weight_decay", a.weightDecay, 0.0, 1.0);
        a.loss = valueNamed(adamLosses(), r.choiceOr("loss", adamLossName(a.loss), valueNames(adamLosses())));
        a.debiasTargets = r.booleanOr("debias_targets", a.debiasTargets);
        a.patience = int(r.integerOr("patience", a.patience, 0, kMaxEpochs));
        a.patienceLrFraction = r.numberOr("patience_lr_fraction", a.patienceLrFraction, 0.0, 1.0, true);
    } else {
        LevenbergMarquardtConfig& l = c.lm;
        l.mu = r.numberOr("mu", l.mu, 0.0, kInf, true);
        l.muDec = r.numberOr("mu_dec", l.muDec, 0.0, 1.0, true);
        l.muInc = r.numberOr("mu_inc", l.muInc, 1.0, kInf, true);
        l.muMax = r.numberOr("mu_max", l.muMax, 0.0, kInf, true);
        l.minGrad = r.numberOr("min_grad", l.minGrad, 0.0, kInf);
        l.maxFail = int(r.integerOr("max_fail", l.maxFail, 1, kMaxEpochs));
        l.goal = r.numberOr("goal", l.goal, 0.0, kInf);
        l.maxEpochGflop = r.numberOr("max_epoch_gflop", l.maxEpochGflop, 0.0, kInf);
        if (l.mu > l.muMax) throw InputError(r.file(), JsonReader::child(r.pointer(), "mu"), "initial mu exceeds mu_max");
    }
    return c;
}

json toJson(const TrainerConfig& c) {
    json j;
    if (c.type == TrainerType::Adam) {
        const AdamConfig& a = c.adam;
        j = json{{"type", c.typeName()},
                 {"batch_size", a.batchSize},
                 {"learning_rate", a.learningRate},
                 {"min_learning_rate", a.minLearningRate},
                 {"schedule", nameOf(lrSchedules(), a.schedule)},
                 {"step_epochs", a.stepEpochs},
                 {"step_gamma", a.stepGamma},
                 {"beta1", a.beta1},
                 {"beta2", a.beta2},
                 {"epsilon", a.epsilon},
                 {"weight_decay", a.weightDecay},
                 {"loss", adamLossName(a.loss)},
                 {"debias_targets", a.debiasTargets},
                 {"patience", a.patience},
                 {"patience_lr_fraction", a.patienceLrFraction}};
    } else {
        const LevenbergMarquardtConfig& l = c.lm;
        j = json{{"type", c.typeName()},
                 {"mu", l.mu},
                 {"mu_dec", l.muDec},
                 {"mu_inc", l.muInc},
                 {"mu_max", l.muMax},
                 {"min_grad", l.minGrad},
                 {"max_fail", l.maxFail},
                 {"goal", l.goal},
                 {"max_epoch_gflop", l.maxEpochGflop}};
    }
    writeCommon(c.common(), j);
    return j;
}

}  // namespace rrf
