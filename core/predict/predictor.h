#pragma once
/// CPU prediction (docs/design.md §13): every covered pixel of a G-buffer is
/// evaluated with its object's networks, batched per object (PartitionedNetwork::predict: each
/// pixel's kd-tree leaf is looked up and its network evaluated, Eigen GEMMs per leaf),
/// giving the direct, indirect and global images.
///
/// What each term comes from depends on the networks an object has (network "targets"):
///   separate  direct and indirect nets → direct, indirect, global = direct + indirect
///   joint     one 6-output net         → outputs 0–2 direct, 3–5 indirect, global = sum
///   global    one net                  → global only; direct and indirect are unavailable
///   direct / indirect only             → that term only
/// With "prediction": {"direct": "exact"} (the default) the direct term is computed instead
/// (core/predict/exact_direct.h: closed-form unshadowed light times a visibility ratio from
/// `direct_samples` shadow rays per light) and the networks supply only indirect light, as in Ren et
/// al. 2013.
///
/// Emitter pixels show the emitted radiance (direct term), as the ground truth does; background pixels
/// are black. Pixels of objects without a network are black and counted; a term that some covered
/// pixels cannot get is reported unavailable (the image still holds what could be predicted).
/// Non-finite network outputs are replaced by 0 and counted, never written.
///
/// Pixels of sharply glossy objects (PredictionSettings::gather) take their indirect light from the
/// glossy gather instead of their own network: one more bounce, then the networks and exact direct
/// light where it lands (core/predict/glossy_gather.h).
///
/// Deterministic: batches are fixed chunks of each object's pixels in ascending order, so the images
/// are bit-identical for any thread count.

#include <cstdint>
#include <string>
#include <vector>

#include "core/predict/gbuffer.h"
#include "core/predict/prediction_settings.h"
#include "core/util/image.h"
#include "core/nn/model_set.h"
#include "core/render/term.h"
#include "core/scene/scene.h"

namespace rrf {

struct Prediction {
    Image images[kTermCount];            ///< direct, indirect, global (index with int(Term))
    bool available[kTermCount] = {true, true, true};  ///< false: some covered pixel lacks this term
    std::vector<std::string> unavailableWhy;  ///< one line per unavailable term
    std::vector<int> objectsWithoutNetwork;    ///< visible objects with no network at all (shown black)
    uint64_t pixelsWithoutNetwork = 0;
    /// Non-finite values kept out of the images (replaced by 0): network outputs and exact direct
    /// light of a pixel.
    uint64_t nonFinite = 0;
    uint64_t pixelsPredicted = 0;        ///< pixels evaluated by at least one network
    /// Per pixel (row-major, top row first): the kd-tree leaf that predicted it, in the tree of the
    /// object's indirect network (else global, else direct); −1 where no network ran. The view's
    /// "leaf" overlay colours pixels by (object, leaf).
    std::vector<int> leaf;
    double inferenceSeconds = 0.0;       ///< network evaluation
    double directSeconds = 0.0;          ///< exact direct light (0 in network mode)
    /// Glossy gather (core/predict/glossy_gather.h): pixels whose indirect light was gathered, and
    /// the time it took (secondary rays, networks and exact direct light there).
    uint64_t pixelsGathered = 0;
    double gatherSeconds = 0.0;
    /// Ensemble spread (core/predict/member_spread.h): per pixel the members' standard deviation of
    /// the networks' part of the global term (RGB, radiance). Computed when some network of the
    /// model set has members' outputs; otherwise empty (0 × 0). Pixels without one (objects whose
    /// networks are single, gathered pixels, emitters, background) hold 0 and spreadKnown 0.
    Image spread;
    std::vector<uint8_t> spreadKnown;  ///< per pixel: 1 where `spread` is the members' spread
    uint64_t spreadPixels = 0;         ///< pixels with spreadKnown 1
    double spreadSeconds = 0.0;        ///< the members' extra forward passes (wall time; not in inferenceSeconds)

    const Image& image(Term t) const { return images[int(t)]; }
};

/// The objects whose pixels `settings` gather with `models` (ascending ids): the glossy gather's rule
/// (GlossyGather::gathers) and a network plan whose global image is direct + indirect (an object
/// with only a global network, or without networks, keeps what it has). Predictor::predict gathers
/// exactly these; the workbench asks it whether a CPU frame should follow the GLSL one.
std::vector<int> gatheredObjects(const Scene& scene, const ModelSet& models, const PredictionSettings& settings);

class Predictor {
public:
    /// `scene` and `models` must outlive the predictor. Models are matched to objects by id; their
    /// input count must equal the scene's record layout (loadModelSet already checks the layout).
    /// Throws std::invalid_argument if a network's input or output count does not fit.
    Predictor(const Scene& scene, const ModelSet& models, const PredictionSettings& settings = {});

    /// G-buffer of the scene's camera at width × height with the movable light centred at `lightPos`.
    GBuffer gbuffer(const Vec3& lightPos, int width, int height) const;
    /// Evaluates the networks (and the exact direct light if chosen) over `gb`.
    Prediction predict(const GBuffer& gb) const;
    /// Prediction::leaf without evaluating any network: per pixel of `gb` the kd-tree leaf of its
    /// object's indirect model (else global, else direct), −1 where no network would run.
    std::vector<int> leaves(const GBuffer& gb) const;

    const PredictionSettings& settings() const { return settings_; }
    const RecordLayout& layout() const { return layout_; }
    const PathTracer& tracer() const { return tracer_; }
    const Scene& scene() const { return scene_; }
    /// One line per object: which networks it has ("separate", "joint", ..., or "none").
    std::vector<std::string> describe() const;

private:
    /// The networks and exact direct light (with `directSamples`, keyed by `seed`) over `gb`, without
    /// the gather.
    /// `withSpread`: also the members' spread of networks that have it.
    Prediction predictTerms(const GBuffer& gb, int directSamples, uint64_t seed, bool withSpread) const;
    /// Replaces the indirect (and global) term of gathered objects' pixels (core/predict/glossy_gather.h).
    /// `depth` 0 for the camera's pixels, 1 for the gather's secondary points (which gather once
    /// more, with PredictionSettings::Gather's second-bounce sample counts, and no further).
    /// `seed` keys its directions: the prediction's seed for the camera's pixels, one per batch below.
    void gather(const GBuffer& gb, Prediction& pr, int depth, uint64_t seed) const;

    const Scene& scene_;
    const ModelSet& models_;
    PredictionSettings settings_;
    RecordLayout layout_;
    Accel accel_;
    PathTracer tracer_;  ///< NEE, one bounce: primary rays and exact direct light
    std::vector<int> gathered_;  ///< gatheredObjects(): the objects whose indirect light is gathered
    bool spread_ = false;        ///< some network of the model set has members' outputs (Prediction::spread)
};

}  // namespace rrf
