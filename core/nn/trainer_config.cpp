#include "core/nn/trainer_config.h"

#include <stdexcept>

#include "core/nn/trainers/registry.h"
#include "core/util/error.h"

namespace rrf {

const char* adamLossName(AdamLoss loss) { return nameOf(adamLosses(), loss); }

const char* TrainerConfig::typeName() const { return trainerTypeInfo(type).name; }

TrainerConfig TrainerConfig::projectDefault() {
    TrainerConfig t = TrainerConfig().withType(TrainerType::Adam);
    t.adam.loss = AdamLoss::RelativeL2;
    t.adam.errorGoal = 0.02;
    t.adam.maxEpochs = 600;
    return t;
}

TrainerConfig TrainerConfig::withType(TrainerType t) const {
    TrainerConfig c = *this;
    c.type = t;
    return c;
}

TrainerConfig TrainerConfig::withType(const std::string& name, const std::string& setting) const {
    const TrainerTypeInfo* info = findTrainerType(name);
    if (!info) throw SettingError(setting, "unknown trainer '" + name + "' (expected " + trainerShortNamesText() + ")");
    return withType(info->type);
}

}  // namespace rrf
