#pragma once
/// Reference store (docs/design.md §14a): converged path-traced references, rendered once and kept
/// with the project, reused by `rrf evaluate`, `rrf sweep`, `rrf pipeline` and the workbench.
///
/// A reference is determined by its ReferenceKey (scene content, camera, light position, resolution,
/// estimator, path depth, seed): the same key always gives the same pixels (the renderer's sample k
/// of pixel i is Rng(seed, i, k)), so a stored one is never recomputed. A changed scene has another
/// content hash, hence another key: its old references are "stale" (listed, pruned on request), never
/// used for it.
///
/// How long a reference renders is set by a NoiseTarget, not a fixed spp: passes run until the
/// reference's own expected error — its relative RMSE noise floor on the global term, over the
/// footprint mask of the evaluation (core/predict/footprint_mask.h), with the formula of
/// core/eval/error_metrics.h — is at or below the target, or the spp cap is reached. The reached
/// noise and spp are stored and printed. A stored reference that falls short of a stricter target is
/// continued from its saved sums (more passes), not re-rendered; a cancelled render is saved as such a
/// partial entry and resumes the same way. The result is bit-identical to an uninterrupted render.
///
/// On disk, one directory per key under the store's directory:
///   <store>/<key id>/reference.json   key, spp, reached noise per term, seconds, complete flag, the
///                                      noise it was rendered to, the state file's checksum
///   <store>/<key id>/{direct,indirect,global}.exr, variance_<term>.exr and render.json
///                                      (a directory `rrf evaluate --reference` and loadReference read)
///   <store>/<key id>/state.rrfs       the renderer's per-pixel sums (checksummed), for resuming; the
///                                      pixels obtain() returns are computed from it
/// An entry is written whole (a temporary directory renamed into place), never mixed. A damaged entry
/// (unreadable JSON, a state file whose size or checksum is wrong) is an InputError naming the file.
/// core/eval/reference_store_file.h reads and writes the JSON files of an entry.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/eval/evaluation.h"
#include "core/eval/reference_noise.h"
#include "core/eval/reference_settings.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

namespace rrf {

/// Everything that determines a reference's pixels.
struct ReferenceKey {
    uint64_t sceneHash = 0;   ///< Scene::contentHash() of the scene as rendered (overrides applied)
    uint64_t cameraHash = 0;  ///< hash of the camera (eye, target, up, fov)
    Vec3 lightPosition{0.f};  ///< the movable light's centre
    int width = 0, height = 0;
    Estimator estimator = Estimator::NEE;
    int maxDepth = 64;
    uint64_t seed = 1;

    /// The key of `scene` rendered with the movable light at `lightPosition` (as Scene::setLightPosition
    /// places it) at width × height with `render`'s estimator, depth and seed.
    static ReferenceKey of(const Scene& scene, const Vec3& lightPosition, int width, int height,
                           const RenderSettings& render);
    /// A 16-hex-digit digest of every field: the entry's directory name.
    std::string id() const;
    bool operator==(const ReferenceKey& o) const;
};

/// A stored reference as listed by the store.
struct StoredReference {
    ReferenceKey key;
    std::string dir;          ///< the entry's directory
    int spp = 0;
    double seconds = 0;       ///< total render time over all sessions
    ReferenceNoise noise;
    bool complete = false;    ///< reached its target or its cap (false: cancelled, resumable)
    double wantedNoise = 0;   ///< the global relative RMSE noise it was rendered towards
    bool stale = false;       ///< its scene hash differs from the one list() was asked about
    /// Non-empty when the entry cannot be read (list() only; the InputError's message). pruneStale
    /// removes such entries too.
    std::string problem;
};

/// Progress of a reference render, for a progress line or a job bar (called on the rendering thread).
struct ReferenceProgress {
    int spp = 0, sppCap = 0;
    double noise = 0, target = 0;  ///< current and wanted relative RMSE noise (global term)
    double seconds = 0;
    /// Fraction done, estimated from the noise (noise ∝ 1/√spp): spp needed ≈ spp·(noise/target)².
    double fraction = 0;
    double etaSeconds = 0;
};

class ReferenceStore {
public:
    /// A store in `dir` (created on first write). Projects keep theirs in <project dir>/references.
    explicit ReferenceStore(std::string dir);
    const std::string& dir() const { return dir_; }

    /// The stored entry for `key`, complete or not; nullopt if none.
    std::optional<StoredReference> find(const ReferenceKey& key) const;
    /// Every entry, marked stale when its scene hash differs from `currentSceneHash`.
    std::vector<StoredReference> list(uint64_t currentSceneHash) const;
    /// Removes the stale and the unreadable entries and left-over temporary directories of an
    /// interrupted write; returns how many entries.
    int pruneStale(uint64_t currentSceneHash);

    /// The reference for `key`, with its variances: the stored one when it meets `target` (its noise
    /// ≤ the wanted noise, or its spp at the cap); otherwise rendered, or continued from the stored
    /// sums, until it does, then saved. `scene` must hash to key.sceneHash (std::invalid_argument
    /// otherwise). `measuredError` (optional) returns the relative RMSE of whatever is being measured
    /// against the reference so far; the wanted noise is then max(target.relativeRmse,
    /// target.errorFraction × that error). `log` receives one line when the store renders or
    /// continues (never silent) and one when it reuses. When `cancel` becomes true the render stops
    /// within one pass, the partial entry is saved (resumable) and the result has cancelled = true.
    Reference obtain(const Scene& scene, const ReferenceKey& key, const NoiseTarget& target,
                     const std::atomic<bool>* cancel = nullptr,
                     const std::function<void(const ReferenceProgress&)>& progress = {},
                     const std::function<double(const Reference&)>& measuredError = {},
                     const std::function<void(const std::string&)>& log = {});

private:
    std::string dir_;
};

}  // namespace rrf
