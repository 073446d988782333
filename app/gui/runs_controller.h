#pragma once
/// The project's runs as the workbench acts on them: saving the ground truth shown as a render run,
/// comparing the views with a run (its images as the comparison, or a training run's models as the
/// prediction), re-opening a run (its settings restored, its images shown as the ground truth) and
/// exporting the images on screen. It starts no jobs of its own: it reads the ground truth's
/// session and hands models to the prediction. UI thread only.

#include <functional>
#include <memory>
#include <string>

#include "app/gui/controller_context.h"

namespace rrf {

class GroundTruthController;
class PredictionController;
class RenderSession;
struct Image;
struct Run;

class RunsController {
public:
    /// `sceneChanged`: the workbench's reaction to a scene the controller changed (a re-opened run's
    /// light or overrides): the prediction follows, the picking data is rebuilt where needed.
    RunsController(ControllerContext& ctx, GroundTruthController& groundTruth, PredictionController& prediction,
                   std::function<void()> sceneChanged);

    /// Records the current ground truth as a run (files under <project dir>/runs/<id>/).
    bool saveRun();
    /// Compares the views with project.runs[index]: a render run's images become the comparison,
    /// a training run's settings and models the prediction.
    bool compareRun(int index);
    /// Restores project.runs[index]'s settings; a render run's images become the ground truth, a
    /// training run's models the prediction.
    bool reopenRun(int index);
    /// Writes the ground truth (EXR and PNG), `error` (the error map on screen, when not empty) and
    /// the prediction's images into `dir`, as one set.
    bool exportImages(const std::string& dir, const Image& error);

private:
    /// The ground truth's render when it has finished and is of the scene as it is; else null, with
    /// a notice at `panel` saying why `action` cannot use it.
    std::shared_ptr<RenderSession> finishedRender(const std::string& action, const char* panel);
    /// A training run "opens" as its settings and its models.
    bool loadTrainRun(const Run& run);

    ControllerContext& ctx_;
    panels::WorkbenchState& state_;  ///< ctx_.state
    GroundTruthController& groundTruth_;
    PredictionController& prediction_;
    std::function<void()> sceneChanged_;
};

}  // namespace rrf
