#pragma once
/// References and evaluation reports shared by `rrf evaluate`, `rrf pipeline` and `rrf reference`:
/// references from the project's reference store (rendered to a noise target, with a progress line)
/// or at a fixed spp, and per-light maps, JSON and tables with a held-out summary.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/evaluation.h"
#include "core/eval/reference_store.h"
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


/// The project's noise target ("reference" section) with --noise and --spp-cap applied where > 0.
NoiseTarget noiseTargetFor(const Project& p, double noise, int sppCap);

/// The size of the project's references: the flags where > 0, else the "reference" section's, else
/// the "render" section's, else the camera's.
std::pair<int, int> referenceSize(const Project& p, int width, int height);

/// A reference and what the report says about where it came from (null: nothing to add).
struct ObtainedReference {
    Reference reference;
    nlohmann::json info;
};

/// Obtains the reference at `lp` from `store` with a progress line labelled `label`, printing the
/// store's lines (rendered, continued or reused) and then the reference's spp, seconds and reached
/// noise per term. `measuredError` as in ReferenceStore::obtain. Throws if interrupted (the partial
/// reference is saved and the next call continues it).
ObtainedReference obtainWithProgress(ReferenceStore& store, const Project& p, const Vec3& lp, int width, int height,
                                     const NoiseTarget& target, const std::function<double(const Reference&)>& measuredError,
                                     const std::string& label);

/// The error the noise target is relative to (ReferenceStore::obtain's measuredError): the global
/// relative RMSE of `predictor` against the reference so far, noise-corrected where the noise is
/// known (the raw figure would count the reference's own noise as the model's error).
double measuredGlobalError(const Predictor& predictor, const Reference& reference);

/// measuredGlobalError for one light while its reference converges: the prediction is made at the
/// first call and compared with every later state of the reference (a glossy gather's CPU frame
/// takes seconds; the reference store asks after every pass).
class MeasuredErrorOfOnePrediction {
public:
    explicit MeasuredErrorOfOnePrediction(const Predictor& predictor) : predictor_(predictor) {}
    double operator()(const Reference& reference);

private:
    const Predictor& predictor_;
    Vec3 light_{0.f};  ///< the light position the prediction was made for (the G-buffer may store another)
    std::optional<GBuffer> gb_;
    Prediction prediction_;
};

/// Where evaluateAll gets the reference of light `k` at position `light`.
using ReferenceSource = std::function<ObtainedReference(size_t k, const Vec3& light)>;

/// A ReferenceSource from the project's store, with the measured-error hook of `predictor`.
ReferenceSource storeSource(ReferenceStore& store, const Project& p, const Predictor& predictor, int width, int height,
                            const NoiseTarget& target, size_t lightCount);
/// A ReferenceSource rendering at fixed spp (`ro`), no noise target and no store.
ReferenceSource fixedSppSource(const Project& p, const RenderOptions& ro, size_t lightCount);

/// Evaluates at each light position (references from `source`), writes maps and reports and prints
/// the tables; returns the evaluations. With one position the files go to `out`, otherwise to
/// out/light_<k> plus a held-out summary in `out`.
std::vector<Evaluation> evaluateAll(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                    const ReferenceSource& source, const std::string& out, float exposure);

}  // namespace rrf::cli
