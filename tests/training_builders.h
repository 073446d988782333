#pragma once
/// The training options the engine tests were written for, which are not the project's defaults
/// (ObjectTrainingOptions' initialisers: Adam, indirect-light networks in kd-trees): one network per
/// object for the total radiance, trained by Levenberg–Marquardt with a trainer object's own defaults.
/// A test that starts from these and changes what it tests keeps its bounds and counts whatever the
/// project's defaults become.

#include "core/nn/object_training.h"
#include "core/nn/trainer_config.h"

namespace rrf::test {

/// One Levenberg–Marquardt network per object and target (TargetMode::Global), no kd-tree; when a
/// test allows leaves (maxLeaves > 1) every split is kept (minSplitGain 0).
inline ObjectTrainingOptions plainTraining() {
    ObjectTrainingOptions o;
    o.targets = TargetMode::Global;
    o.trainer = TrainerConfig();  // a trainer object without keys: Levenberg–Marquardt
    o.partition.maxLeaves = 1;
    o.partition.minSplitGain = 0;
    return o;
}

}  // namespace rrf::test
