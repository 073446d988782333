#pragma once
/// The project's runs as the workbench acts on them: saving the ground truth shown as a render run,
/// comparing the views with a run (its images as the comparison, or a training run's models as the
/// prediction), re-opening a run (its settings restored, its images shown as the ground truth) and
/// exporting the images on screen. A render run's images are read on a worker (a ReadBack job,
/// app/gui/read_back.h) and shown when they arrive; a training run's models are read by the
/// prediction's own read-back. UI thread only.

#include <functional>
#include <memory>
#include <string>

#include "app/gui/controller_context.h"
#include "app/gui/read_back.h"

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
    ~RunsController();

    /// Records the current ground truth as a run (files under <project dir>/runs/<id>/).
    bool saveRun();
    /// Compares the views with project.runs[index]: a render run's images become the comparison,
    /// a training run's settings and models the prediction. The images and models are read on a
    /// worker and shown when they arrive (true: the read started; a read that fails says so then).
    bool compareRun(int index);
    /// Restores project.runs[index]'s settings; a render run's images become the ground truth, a
    /// training run's models the prediction. A render run's settings are restored together with
    /// its images, once they have been read on a worker (nothing changes when they cannot be).
    bool reopenRun(int index);
    /// Each frame: shows a run's images that have arrived.
    void poll();
    /// True while a run's images are being read.
    bool loading() const { return runImages_.pending(); }
    /// Forgets a read in flight (another project was opened).
    void drop() { runImages_.drop(); }
    /// Writes the ground truth (EXR and PNG), `error` (the error map on screen, when not empty) and
    /// the prediction's images into `dir`, as one set.
    bool exportImages(const std::string& dir, const Image& error);

private:
    /// The ground truth's render when it has finished and is of the scene as it is; else null, with
    /// a notice at `panel` saying why `action` cannot use it.
    std::shared_ptr<RenderSession> finishedRender(const std::string& action, const char* panel);
    /// A training run "opens" as its settings and its models.
    bool loadTrainRun(const Run& run);
    struct RunImages;
    /// Reads the images of render run project.runs[index] on a worker; `then` shows them when they
    /// arrive (a failure is a notice naming `action` and the file instead).
    bool readRunImages(int index, const char* action, std::function<void(RunImages&)> then);
    /// A re-opened render run's settings restored and its images shown as the ground truth.
    void showReopenedRun(RunImages& r);

    ControllerContext& ctx_;
    panels::WorkbenchState& state_;  ///< ctx_.state
    GroundTruthController& groundTruth_;
    PredictionController& prediction_;
    std::function<void()> sceneChanged_;
    ReadBack<RunImages> runImages_;  ///< a compared or re-opened render run's images on their way
};

}  // namespace rrf
