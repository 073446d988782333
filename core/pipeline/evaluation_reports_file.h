#pragma once
/// The report files of the evaluation stages (core/pipeline/evaluate_stage.h): evaluation.json per
/// light, held_out.json over several lights and light_grid.json, in the formats docs/file-formats.md
/// describes.

#include <string>
#include <vector>

#include "core/eval/evaluation.h"
#include "core/eval/held_out.h"
#include "core/eval/light_grid.h"
#include "core/pipeline/evaluate_stage.h"
#include "core/util/json_text.h"

namespace rrf {

/// The reports of one run of evaluateAtLights: each light's evaluation.json, kept to be listed
/// again in held_out.json.
class EvaluationReports {
public:
    /// Writes `file` (the evaluation.json of one light): `e`'s report (core/eval/evaluation_json.h)
    /// with where its reference came from ("reference_source", unless `origin` is empty) and the
    /// images written for it ("images"). Throws std::runtime_error when it cannot be written.
    void writeLight(const std::string& file, const Scene& scene, const Evaluation& e, const ReferenceOrigin& origin,
                    const EvaluationImages& images);
    /// Writes `file` (held_out.json): {"summary", "flip", "uncertainty"} of `s` and "evaluations",
    /// every report writeLight wrote, in order.
    void writeHeldOut(const std::string& file, const Scene& scene, const HeldOutSummary& s) const;

private:
    std::vector<JsonText> reports_;
};

/// One slice image of a light-grid map: the y of its lights and the image's file name.
struct LightGridSlice {
    double y = 0;
    std::string image;
};

/// Writes `file` (light_grid.json): `map`'s figures (core/eval/light_grid_json.h) and "slices",
/// [{"y", "image"}]. Throws std::runtime_error when it cannot be written.
void writeLightGridReport(const std::string& file, const Scene& scene, const LightGridMap& map,
                          const std::vector<LightGridSlice>& slices);

}  // namespace rrf
