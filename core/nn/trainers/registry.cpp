#include "core/nn/trainers/registry.h"

namespace rrf {

namespace {
/// A trainer's own keys after "type" and the keys of TrainerCommon, which every trainer has.
std::vector<std::string> withCommonKeys(std::vector<std::string> own) {
    own.insert(own.begin(), {"type", "max_epochs", "error_goal", "max_samples", "seed"});
    return own;
}
}  // namespace

const std::vector<TrainerTypeInfo>& trainerTypes() {
    static const std::vector<TrainerTypeInfo> types = {
        {TrainerType::LevenbergMarquardt, "levenberg_marquardt", "lm",
         withCommonKeys({"mu", "mu_dec", "mu_inc", "mu_max", "min_grad", "max_fail", "goal", "max_epoch_gflop"})},
        {TrainerType::Adam, "adam", nullptr,
         withCommonKeys({"batch_size", "learning_rate", "min_learning_rate", "schedule", "step_epochs", "step_gamma",
                         "beta1", "beta2", "epsilon", "weight_decay", "loss", "debias_targets", "patience",
                         "patience_lr_fraction"})},
    };
    return types;
}

const TrainerTypeInfo& trainerTypeInfo(TrainerType type) {
    for (const TrainerTypeInfo& t : trainerTypes())
        if (t.type == type) return t;
    return trainerTypes().front();
}

const TrainerTypeInfo* findTrainerType(const std::string& name) {
    for (const TrainerTypeInfo& t : trainerTypes())
        if (name == t.name || (t.shortName && name == t.shortName)) return &t;
    return nullptr;
}

std::vector<std::string> trainerShortNames() {
    std::vector<std::string> names;
    for (const TrainerTypeInfo& t : trainerTypes()) names.push_back(t.shortName ? t.shortName : t.name);
    return names;
}

std::string trainerShortNamesText() {
    const std::vector<std::string> names = trainerShortNames();
    std::string s;
    for (size_t k = 0; k < names.size(); ++k) s += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
    return s;
}

std::vector<std::string> trainerTypeNames() {
    std::vector<std::string> names;
    for (const TrainerTypeInfo& t : trainerTypes()) {
        names.push_back(t.name);
        if (t.shortName) names.push_back(t.shortName);
    }
    return names;
}

const std::vector<NamedValue<AdamLoss>>& adamLosses() {
    static const std::vector<NamedValue<AdamLoss>> losses = {{AdamLoss::Mse, "mse"},
                                                             {AdamLoss::RelativeL2, "relative_l2"},
                                                             {AdamLoss::RelativeL2Prediction, "relative_l2_prediction"}};
    return losses;
}

const std::vector<NamedValue<LrSchedule>>& lrSchedules() {
    static const std::vector<NamedValue<LrSchedule>> schedules = {
        {LrSchedule::Constant, "constant"}, {LrSchedule::Step, "step"}, {LrSchedule::Cosine, "cosine"}};
    return schedules;
}

}  // namespace rrf
