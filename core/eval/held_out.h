#pragma once
/// Held-out light positions (docs/design.md §15): evaluation at K light positions drawn
/// from the light region on a random stream that the data generator never uses, and the spread
/// (mean, min, max) of the errors across them — the generalisation a user cares about.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/evaluation.h"

namespace rrf {

/// K positions uniform in `region` (a single point when the region is empty or degenerate in an
/// axis), a pure function of (region, k, seed). The stream is domain-separated from the generator's
/// record stream, so for the same seed these are not the training positions.
std::vector<Vec3> heldOutLightPositions(const Bounds3& region, int k, uint64_t seed);

struct Spread {
    double mean = 0, min = 0, max = 0;
    int count = 0;  ///< evaluations in which the object was visible
    void add(double v);
    nlohmann::json toJson() const { return {{"mean", mean}, {"min", min}, {"max", max}, {"count", count}}; }
};

/// Spread of RMSE and relative RMSE per term, per object and overall, across evaluations.
struct HeldOutSummary {
    struct Row {
        Spread rmse, relativeRmse;
    };
    bool available[kTermCount] = {true, true, true};
    std::vector<Row> perObject[kTermCount];  ///< index = object id
    Row overall[kTermCount];
};

HeldOutSummary summarizeHeldOut(const std::vector<Evaluation>& evaluations, size_t objectCount);
nlohmann::json heldOutJson(const Scene& scene, const HeldOutSummary& s);
/// Fixed-width table: term, object, relative RMSE mean/min/max, RMSE mean/min/max.
std::string heldOutTable(const Scene& scene, const HeldOutSummary& s);

}  // namespace rrf
