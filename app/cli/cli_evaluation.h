#pragma once
/// References and evaluation reports shared by `rrf evaluate`, `rrf pipeline` and `rrf reference`:
/// the stages of core/pipeline/evaluate_stage.h under the CLI's progress lines, their notes printed.

#include <string>
#include <vector>

#include "core/pipeline/evaluate_stage.h"

namespace rrf::cli {

/// Renders a reference at light position `lp`, with a progress line labelled `label`; throws if
/// interrupted.
Reference renderWithProgress(const Scene& scene, const Vec3& lp, const RenderOptions& o, const std::string& label);

/// obtainReference (core/pipeline/evaluate_stage.h) under a progress line labelled `label`, its lines
/// printed. Throws if interrupted (the partial reference is saved and the next call continues it).
ObtainedReference obtainWithProgress(ReferenceStore& store, const Project& p, const Vec3& lp, int width, int height,
                                     const NoiseTarget& target, const std::function<double(const Reference&)>& measuredError,
                                     const std::string& label);

/// A ReferenceSource from the project's store, with the measured-error hook of `predictor`.
ReferenceSource storeSource(ReferenceStore& store, const Project& p, const Predictor& predictor, int width, int height,
                            const NoiseTarget& target, size_t lightCount);
/// A ReferenceSource rendering at fixed spp (`ro`), no noise target and no store.
ReferenceSource fixedSppSource(const Project& p, const RenderOptions& ro, size_t lightCount);

/// evaluateAtLights (core/pipeline/evaluate_stage.h) with its tables and lines printed.
std::vector<Evaluation> evaluateAll(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                    const ReferenceSource& source, const std::string& out, float exposure);

/// evaluateLightGrid (core/pipeline/evaluate_stage.h) with its tables and lines printed.
LightGridOutcome lightGrid(const Project& p, const Predictor& predictor, const LightGridSpec& grid,
                           const ReferenceSource& source, const std::string& out, float exposure, const LightGridMarks& marks);

}  // namespace rrf::cli
