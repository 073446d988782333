#include "app/gui/live_prediction.h"

#include "app/gl/glsl_predictor.h"

namespace rrf {

LivePrediction::LivePrediction() = default;
LivePrediction::~LivePrediction() = default;

void LivePrediction::load(const Scene& scene, const std::string& dir, bool tryGlsl, std::string& glslError,
                          std::shared_ptr<const ModelSet> preloaded) {
    reset();
    std::shared_ptr<const ModelSet> models =
        preloaded ? std::move(preloaded) : std::make_shared<const ModelSet>(loadModelSet(dir, scene.contentHash()));
    if (models->objects.empty()) throw std::runtime_error(dir + ": the model set holds no networks");
    if (tryGlsl) {
        try {
            glsl_ = std::make_unique<GlslPredictor>(scene, *models);
        } catch (const std::exception& e) {
            glslError = e.what();
            glsl_.reset();
        }
    }
    models_ = std::move(models);
    dir_ = dir;
    sceneHash_ = scene.contentHash();
}

void LivePrediction::reset() {
    glsl_.reset();  // before the models it was built from
    models_.reset();
    dir_.clear();
    sceneHash_ = 0;
}

double LivePrediction::renderGlsl(const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction,
                                Image out[kTermCount]) {
    const double seconds = renderGlslRows(camera, lightPos, prediction, 0, camera.height);
    readGlsl(out);
    return seconds;
}

double LivePrediction::renderGlslRows(const Camera& camera, const Vec3& lightPos, const PredictionSettings& prediction,
                                      int rowBegin, int rowEnd) {
    const Camera& current = glsl_->camera();
    if (current.width != camera.width || current.height != camera.height || !(current.eye == camera.eye) ||
        !(current.target == camera.target) || !(current.up == camera.up) || current.fovYDegrees != camera.fovYDegrees)
        glsl_->setCamera(camera);
    // Moving the light re-uploads its geometry (and the shader's shadow casters): not per band.
    if (!(glsl_->lightPosition() == lightPos)) glsl_->setLightPosition(lightPos);
    glsl_->setPrediction(prediction);
    // Image rows count from the top, GL's from the bottom.
    glsl_->render(camera.height - rowEnd, camera.height - rowBegin);
    return glsl_->frameSeconds();
}

void LivePrediction::readGlsl(Image out[kTermCount]) const {
    for (Term t : kTerms) out[int(t)] = glsl_->read(t);
}

}  // namespace rrf
