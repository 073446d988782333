#pragma once
/// The reference and evaluation stages: references from the project's store (converged to a noise
/// target relative to the model's error) or at a fixed spp, and a model's prediction judged against
/// them at one light or at held-out lights, with the per-light maps, JSON and tables and the held-out
/// summary. `rrf evaluate`, `rrf reference` and `rrf pipeline` run them; the workbench judges against
/// the ground truth its views show with core/eval/evaluation.h directly.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/eval/evaluation.h"
#include "core/eval/light_grid.h"
#include "core/eval/reference_store.h"
#include "core/pipeline/stage_observer.h"
#include "core/predict/predictor.h"
#include "core/project/project.h"
#include "core/render/renderer.h"

namespace rrf {

/// The project's render settings with spp, width and height replaced where > 0.
RenderOptions referenceOptions(const Project& p, int spp, int width, int height);

/// The project's noise target ("reference" section) with noise and spp cap replaced where > 0.
NoiseTarget noiseTargetFor(const Project& p, double noise, int sppCap);

/// The size of the project's references: `width`/`height` where > 0, else the "reference"
/// section's, else the "render" section's, else the camera's.
std::pair<int, int> referenceSize(const Project& p, int width, int height);

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

/// Where a reference came from, as an evaluation report's "reference_source" records it
/// (core/pipeline/evaluation_reports_file.h); a field left empty is not written, and an empty origin
/// adds nothing to the report.
struct ReferenceOrigin {
    /// The store's entry it was obtained from ("store_entry", "id", "spp", "seconds", "noise",
    /// "wanted_noise") and the target it was obtained for ("noise_target").
    std::optional<StoredReference> storeEntry;
    NoiseTarget noiseTarget;
    std::optional<int> fixedSpp;           ///< "fixed_spp": rendered at a fixed spp
    std::optional<uint64_t> seed;          ///< "seed" of that render
    std::optional<std::string> directory;  ///< "directory" it was read from or written to

    bool empty() const { return !storeEntry && !fixedSpp && !seed && !directory; }
};

/// A reference and what the report says about where it came from.
struct ObtainedReference {
    Reference reference;
    ReferenceOrigin info;
};

/// The reference stage: the reference at `lp` from `store` (ReferenceStore::obtain; `measuredError`
/// as there), reporting its progress (fraction and "<spp> spp, noise a -> b") to `observer` and, as
/// notes, the store's lines and then the reference's spp, seconds and reached noise per term.
/// Throws std::runtime_error when cancelled (the partial reference is saved and the next call
/// continues it).
ObtainedReference obtainReference(ReferenceStore& store, const Project& p, const Vec3& lp, int width, int height,
                                  const NoiseTarget& target, const std::function<double(const Reference&)>& measuredError,
                                  const StageObserver& observer);

/// The reference at `lp` rendered at fixed spp (`ro`), no store: progress to `observer`; throws
/// std::runtime_error when cancelled.
ObtainedReference renderFixedReference(const Scene& scene, const Vec3& lp, const RenderOptions& ro, const StageObserver& observer);

/// Where evaluateAtLights gets the reference of light `k` at position `light`.
using ReferenceSource = std::function<ObtainedReference(size_t k, const Vec3& light)>;

/// A ReferenceSource from `store` (obtainReference with the measured-error hook of `predictor`),
/// each light's reference obtained under `run` labelled "reference k/n" (n = `lightCount`).
ReferenceSource storeReferenceSource(ReferenceStore& store, const Project& p, const Predictor& predictor, int width,
                                     int height, const NoiseTarget& target, size_t lightCount, const StageRunner& run);
/// A ReferenceSource rendering at fixed spp (`ro`) under `run`, no noise target and no store.
ReferenceSource fixedSppReferenceSource(const Project& p, const RenderOptions& ro, size_t lightCount, const StageRunner& run);

/// The evaluation stage: `predictor` judged at each light position (references from `source`), the
/// maps, evaluation.json and evaluation.txt written per light (to `out` for one light, else to
/// out/light_<k>) and, for several, held_out.txt and held_out.json in `out`. The tables and a line of
/// prediction times per light go to `observer` as notes. Returns the evaluations; of several, only
/// their figures (per-pixel images, maps and masks are dropped once each light's files are written).
std::vector<Evaluation> evaluateAtLights(const Project& p, const Predictor& predictor, const std::vector<Vec3>& lights,
                                         const ReferenceSource& source, const std::string& out, float exposure,
                                         const StageObserver& observer);

/// Training records' light positions to mark on a light-grid map, and where they came from.
struct LightGridMarks {
    std::vector<Vec3> positions;
    std::string source;  ///< the dataset they were read from ("" when there are none)
    std::string why;     ///< why there are none
};

/// The marks of a light-grid map of `models`: the light positions of (a sample of) the records of
/// the dataset that trained them, when their train run is in the project and the dataset is still
/// there; otherwise none, and why.
LightGridMarks trainingLightMarks(const Project& p, const std::string& models);

/// The light-grid stage (core/eval/light_grid.h): evaluateAtLights at every position of `grid` over
/// the scene's light region (each light's files under out/light_<k>, held_out.* in `out`), then in
/// `out` light_grid.json, light_grid.txt and one slice image per y of the grid, light_grid_y<j>.png
/// (all on one colour scale), with `marks` drawn. The table goes to `observer` as a note.
struct LightGridOutcome {
    std::vector<Evaluation> evaluations;  ///< figures only, as evaluateAtLights returns them for several lights
    LightGridMap map;
};
LightGridOutcome evaluateLightGrid(const Project& p, const Predictor& predictor, const LightGridSpec& grid,
                               const ReferenceSource& source, const std::string& out, float exposure,
                               const LightGridMarks& marks, const StageObserver& observer);

}  // namespace rrf
