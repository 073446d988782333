#pragma once
/// The values a sweep compares (core/pipeline/sweep.h): the kinds, each kind's default series, and every
/// value read into the settings it replaces before anything runs, so a bad value costs no reference
/// render. A value is spelled as outside a JSON file everywhere else (integers, comma-separated
/// lists); a bad one throws SettingError naming "sweep values", an unknown kind "sweep dimension".

#include <string>
#include <vector>

#include "core/data/sampling_settings.h"
#include "core/nn/object_training.h"

namespace rrf {

struct SweepOptions;

/// The kinds of sweep (SweepOptions::what), the one list the CLI's --what and the Cost panel offer.
constexpr const char* kSweepKinds[] = {"spp", "grid", "dirs", "hidden", "trainer", "goal", "leaves", "record_spp", "encoding", "ensemble"};
constexpr int kSweepKindCount = int(sizeof kSweepKinds / sizeof kSweepKinds[0]);

/// The small default series of each kind (kept small so a series runs interactively). Throws
/// SettingError naming "sweep dimension" for an unknown kind.
std::vector<std::string> defaultSweepValues(const std::string& what);

/// One setting of the series, read from its value before anything runs, so a bad value costs no
/// reference render.
struct SweepPoint {
    std::string setting;             ///< the value as given: the row's label
    int spp = 0;                     ///< spp
    SamplingSettings sampling;       ///< grid, dirs, record_spp
    ObjectTrainingOptions training;  ///< hidden, trainer, goal, leaves
};

/// Every value of `o` (o.values, in order) read into its point: o.sampling and o.training with the
/// swept setting replaced. Throws SettingError naming "sweep values" for a malformed value.
std::vector<SweepPoint> sweepPoints(const SweepOptions& o);

}  // namespace rrf
