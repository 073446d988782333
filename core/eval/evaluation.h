#pragma once
/// Evaluation of a prediction against a path-traced reference at the same light position
/// (docs/design.md §14): per term (direct, indirect, global) and per object (masks from the
/// G-buffer's object ids) error statistics, error maps, a JSON report (core/eval/evaluation_json.h)
/// and a readable table. Metric conventions are in core/eval/error_metrics.h.

#include <atomic>
#include <cstdint>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include "core/eval/error_metrics.h"
#include "core/eval/flip_evaluation.h"
#include "core/eval/uncertainty.h"
#include "core/predict/footprint_mask.h"
#include "core/predict/predictor.h"
#include "core/render/term.h"
#include "core/render/renderer.h"

namespace rrf {

/// A ground-truth render (direct, indirect, global) and what made it.
struct Reference {
    Image images[kTermCount];  ///< direct, indirect, global
    /// Per-pixel, per-channel variance of the mean of each term (the renderer's): the reference's own
    /// noise, which every error figure against it reports as its noise floor and subtracts in the
    /// corrected figure (core/eval/error_metrics.h). Empty = unknown (a reference saved without it,
    /// or one of fewer than 2 spp).
    Image variances[kTermCount];
    Vec3 lightPosition{0.f};
    int spp = 0;
    double seconds = 0.0;
    uint64_t nonFinite = 0;    ///< samples the renderer dropped as NaN/Inf
    bool cancelled = false;
    const Image& image(Term t) const { return images[int(t)]; }
    const Image& variance(Term t) const { return variances[int(t)]; }
};

/// The reference a render snapshot holds, with the movable light at `lightPosition`: images, spp,
/// seconds, NaN/Inf count, and the variances when the snapshot's are known (empty = unknown).
Reference referenceOf(const RenderSnapshot& s, const Vec3& lightPosition);

/// A render of a scene with its movable light moved (renderAtLight).
struct LightRender {
    RenderState state;          ///< the renderer's committed sums and counters (resumable, joinable by rows)
    Vec3 lightPosition{0.f};    ///< where the light was (the scene's own when it has none to move)
    bool cancelled = false;     ///< stopped by `cancel` before the last pass
};

/// Renders `scene` with the movable light centred at `lightPos` (the scene itself is not modified),
/// pass by pass to `options.spp`, over the rows `options` select (all, or one process's share:
/// RenderOptions::rowOffset, core/render/render_rows.h); stops before a pass when `cancel` becomes
/// true. `progress` (optional) receives the fraction done after every pass. The one render loop of
/// a reference, whole (renderReference) or split by rows across MPI ranks.
LightRender renderAtLight(const Scene& scene, const Vec3& lightPos, const RenderOptions& options,
                          const std::atomic<bool>* cancel = nullptr, std::atomic<double>* progress = nullptr);

/// Renders the reference of `scene` with the movable light centred at `lightPos` (the scene itself is
/// not modified; renderAtLight). `options.seed` keys the noise; stops early when `cancel` becomes true. `progress`
/// (optional) receives the fraction done after every pass, for a progress line on another thread.
Reference renderReference(const Scene& scene, const Vec3& lightPos, const RenderOptions& options,
                          const std::atomic<bool>* cancel = nullptr, std::atomic<double>* progress = nullptr);

/// Errors of one term: per object (index = object id; pixels = 0 for objects out of view) and over
/// all object pixels ("overall"; emitter and background pixels are exact by construction and left out),
/// both over the pixels the footprint mask keeps.
struct TermErrors {
    bool available = true;
    std::vector<ErrorStats> perObject;
    ErrorStats overall;
};

struct Evaluation {
    Vec3 lightPosition{0.f};
    Prediction prediction;
    TermErrors terms[kTermCount];
    std::vector<int32_t> objectIds;  ///< G-buffer object id per pixel
    /// Which pixels the statistics compare (the kept pixels per object and overall) and how many
    /// object pixels were left out and why: those whose footprint may cover more than one surface,
    /// where the reference's box filter mixes surfaces (core/predict/footprint_mask.h).
    FootprintMask footprint;
    double gbufferSeconds = 0.0;
    double referenceSeconds = 0.0;
    int referenceSpp = 0;
    uint64_t referenceNonFinite = 0;
    bool referenceNoiseKnown = false;  ///< the reference carried its variance (noise floors are numbers)
    /// FLIP of the global term (core/eval/flip_evaluation.h); not available unless the caller ran
    /// flipEvaluation (the CLI's evaluation stage and the workbench's Evaluate do; sweeps do not).
    FlipEvaluation flip;
    /// The ensemble members' spread against the true error (core/eval/uncertainty.h); unavailable
    /// when the prediction carried no spread.
    UncertaintyEvaluation uncertainty;
    const TermErrors& term(Term t) const { return terms[int(t)]; }
};

/// Builds the G-buffer at the reference's light position and size, predicts and compares.
/// Throws std::invalid_argument if the reference has no pixels.
Evaluation evaluate(const Predictor& predictor, const Reference& reference);
/// evaluate() for a prediction already made over `gb` (the reference's light position and size):
/// the comparison only, no network or ray work. A reference that converges pass by pass is
/// compared with one prediction this way (the measured error its noise target follows).
Evaluation evaluatePrediction(const GBuffer& gb, Prediction prediction, const Reference& reference);

/// Fixed-width table: one row per term and object, then the overall row of each term; RMSE and
/// relative RMSE each with "noise floor" and "corrected" columns ("unknown" without the variance);
/// then the FLIP figures when computed.
std::string evaluationTable(const Scene& scene, const Evaluation& e);

/// The files writeEvaluationImages wrote (core/eval/evaluation_json.h lists them in a report).
struct EvaluationImages {
    std::vector<std::string> files;  ///< every file written, in the order written
    /// The value range each PNG's false colours span, by map name ("<kind>_<term>", "flip_hdr_global").
    std::map<std::string, std::pair<double, double>> falseColourRanges;
    uint64_t nonFiniteMapPixels = 0;  ///< non-finite error-map pixels zeroed in the EXR maps
};

/// Writes into `dir`: prediction_<term>.exr/.png, reference_<term>.exr, error_<kind>_<term>.exr (float
/// maps, non-finite pixels zeroed and counted) and error_<kind>_<term>.png (viridis over [0, p99] of
/// the map, the range recorded in the result). Unavailable terms are skipped. With the FLIP
/// figures: flip_hdr_global and flip_ldr_global (.exr, and .png in magma over [0, 1]).
EvaluationImages writeEvaluationImages(const std::string& dir, const Evaluation& e, const Reference& reference,
                                     float exposureStops = 0.f);

/// Writes the prediction images (prediction_<term>.exr and .png) of the available terms into `dir`.
std::vector<std::string> writePredictionImages(const std::string& dir, const Prediction& p, float exposureStops = 0.f);

}  // namespace rrf
