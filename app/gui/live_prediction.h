#pragma once
/// The trained models' prediction for the middle view, kept current as the light moves.
///
/// GLSL path (the normal one): a GlslPredictor (app/gl) built in the workbench window's own GL 3.3
/// context renders the prediction within the frame on the UI thread, so a light drag shows the new
/// prediction in the same frame. The three terms are read back into images because the error map,
/// the hover read-out and the exposure control work on the values, not on a texture.
/// CPU path (fallback, and for exported images): core/Predictor, which the workbench runs as a
/// Predict job when the GLSL path could not be built (missing GL features, a shader error).
/// UI thread only; the ModelSet is shared read-only with CPU jobs.

#include <memory>
#include <string>

#include "core/util/image.h"
#include "core/nn/model_set.h"
#include "core/predict/prediction_settings.h"
#include "core/render/term.h"
#include "core/scene/scene.h"

namespace rrf {

class GlslPredictor;

class LivePrediction {
public:
    LivePrediction();
    ~LivePrediction();
    LivePrediction(const LivePrediction&) = delete;
    LivePrediction& operator=(const LivePrediction&) = delete;

    /// Loads the model directory `dir` for `scene` (rejecting models of another scene: throws,
    /// naming the file) and, when `tryGlsl`, builds the GLSL predictor. A GLSL failure is not an
    /// error: the reason goes to `glslError` and the CPU path is used.
    /// `preloaded`: the set already read from `dir` (by a worker, so the UI thread does not read
    /// weights); null reads it here.
    void load(const Scene& scene, const std::string& dir, bool tryGlsl, std::string& glslError,
              std::shared_ptr<const ModelSet> preloaded = nullptr);
    /// Forgets the models (a new project, or a scene edit that makes them stale).
    void reset();

    bool loaded() const { return models_ != nullptr; }
    bool usesGlsl() const { return glsl_ != nullptr; }
    const std::string& dir() const { return dir_; }
    /// Scene::contentHash() of the scene the models were loaded for.
    uint64_t sceneHash() const { return sceneHash_; }
    std::shared_ptr<const ModelSet> models() const { return models_; }

    /// GLSL path only: renders with `camera` (its width × height), the light at `lightPos` and the
    /// project's `prediction` settings (exact or learned direct light), and returns the images of
    /// every term, out[int(Term)] (top row first); returns the frame's cost in seconds
    /// (GlslPredictor::frameSeconds: its passes' GPU time, plus the CPU's direct light in mode 2).
    /// Throws GlError on GL failure.
    double renderGlsl(const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction,
                    Image out[kTermCount]);
    /// GLSL path only: renders the image rows [rowBegin, rowEnd) (top row first, as images count)
    /// of the frame renderGlsl would render, the other rows kept from earlier bands of the same
    /// camera, light and settings (GlslPredictor::render(rowBegin, rowEnd)); returns the band's
    /// cost in seconds as renderGlsl does. A band that starts at the bottom of the image renders
    /// the G-buffer too, so the bands of a frame go bottom up. Throws GlError on GL failure.
    double renderGlslRows(const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction, int rowBegin,
                          int rowEnd);
    /// GLSL path only: the images of the bands rendered so far, out[int(Term)] (top row first).
    void readGlsl(Image out[kTermCount]) const;

private:
    std::shared_ptr<const ModelSet> models_;
    std::unique_ptr<GlslPredictor> glsl_;
    std::string dir_;
    uint64_t sceneHash_ = 0;
};

}  // namespace rrf
