#pragma once
/// What a pipeline stage (core/pipeline/*_stage.h) tells whoever runs it, and how it is stopped: the
/// one interface between a stage and its front end. The CLI turns it into a progress line and printed
/// notes, the workbench's jobs into a progress bar, a status text, the Log and the live loss plot;
/// sweeps and tests leave it empty. Every callback may be empty and may be called from worker threads
/// (the training's epochs come from several at once), so front ends guard what they share.

#include <atomic>
#include <functional>
#include <string>

#include "core/nn/object_training.h"

namespace rrf {

struct StageObserver {
    /// Set by the front end to stop the stage; it returns within about a second with what it has
    /// (its outcome says it was cancelled) and writes no partial file of its own.
    const std::atomic<bool>* cancel = nullptr;
    /// The stage's fraction done, 0..1 (monotone within one stage).
    std::function<void(double fraction)> progress;
    /// What the stage does now, in a few words ("reading the dataset", "training", "saving the models").
    std::function<void(const std::string& status)> status;
    /// A note worth keeping in a log ("12 records with NaN/Inf dropped from the dataset").
    std::function<void(const std::string& note)> message;
    /// One finished epoch of one network (object id, target name), for live loss curves.
    std::function<void(int objectId, const std::string& target, const EpochRecord& epoch)> epoch;

    bool cancelled() const { return cancel && cancel->load(); }
    void setProgress(double f) const {
        if (progress) progress(f);
    }
    void setStatus(const std::string& s) const {
        if (status) status(s);
    }
    void note(const std::string& m) const {
        if (message) message(m);
    }
};

}  // namespace rrf

namespace rrf {

/// How a front end runs one stage: `stage` called with an observer of the front end's making (the
/// CLI: a progress line labelled `label`; tests: an empty observer). Returns when the stage does
/// and rethrows what it throws.
using StageRunner = std::function<void(const std::string& label, const std::function<void(const StageObserver&)>& stage)>;

/// A StageRunner that calls each stage with `observer` itself (no progress line).
inline StageRunner directRunner(StageObserver observer = {}) {
    return [observer](const std::string&, const std::function<void(const StageObserver&)>& stage) { stage(observer); };
}

}  // namespace rrf
