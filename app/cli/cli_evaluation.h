#pragma once
/// References and evaluation reports shared by `rrf evaluate` and `rrf pipeline`: path-traced
/// references with a progress line, and per-light maps, JSON and tables with a held-out summary.

#include <string>
#include <vector>

#include "core/eval/evaluation.h"
#include "core/predict/predictor.h"
#include "core/render/renderer.h"

namespace rrf {
struct Project;
}

namespace rrf::cli {

/// The project's render settings with spp, width and height replaced where > 0.
RenderOptions referenceOptions(const Project& p, int spp, int width, int height);

/// Renders a reference at light position `lp`, with a progress line labelled `label`; throws if
/// interrupted.
Reference renderWithProgress(const Scene& scene, const Vec3& lp, const RenderOptions& o, const std::string& label);

/// Evaluates at each light position (rendering references with `ro`, or using `given` for a single
/// one), writes maps and reports and prints the tables; returns the evaluations. With one position
/// the files go to `out`, otherwise to out/light_<k> plus a held-out summary in `out`.
std::vector<Evaluation> evaluateAll(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                    const RenderOptions& ro, const Reference* given, const std::string& out, float exposure);

}  // namespace rrf::cli
