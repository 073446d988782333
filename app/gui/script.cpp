#include "app/gui/script.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "app/gl/program_binary_cache.h"
#include "app/gui/prediction_bands.h"
#include "app/gui/workbench.h"
#include "core/nn/network_settings.h"
#include "core/nn/trainers/registry.h"
#include "core/pipeline/presets.h"
#include "core/pipeline/run_recording.h"
#include "core/project/scene_edits.h"
#include "core/util/error.h"
#include "panels/clip_check.h"
#include "panels/pipeline_controls.h"
#include "panels/view_model.h"

namespace rrf {

bool Script::load(const std::string& path, std::string& error) {
    try {
        file_ = path;
        steps_ = readScriptFile(path);
    } catch (const InputError& e) {
        error = e.what();
        steps_.clear();
        return false;
    }
    return true;
}

Script::Status Script::fail(const std::string& message) {
    failed_ = true;
    error_ = "script step " + std::to_string(next_) + " (" + steps_[next_].what + "): " + message;
    return Status::Failed;
}

Script::Status Script::step(Workbench& wb) {
    if (failed_) return Status::Failed;
    if (next_ >= steps_.size()) return Status::Done;
    try {
        if (execute(wb, steps_[next_])) {
            ++next_;
            waiting_ = false;
        }
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    if (failed_) return Status::Failed;
    return next_ >= steps_.size() ? Status::Done : Status::Running;
}

bool Script::execute(Workbench& wb, const ScriptStep& r) {
    panels::WorkbenchState& st = wb.state();
    const std::string& what = r.what;
    auto require = [](bool ok, const std::string& message) {
        if (!ok) throw std::runtime_error(message);
    };

    if (what == "render") {
        // Replaces the running render (e.g. the one started on open): stop it, wait, then start.
        if (wb.renderRunning()) {
            wb.cancelRender();
            return false;
        }
        st.project.render.spp = r.spp.value_or(st.project.render.spp);
        // The image size as the project's "render" section takes it (0: the scene camera's).
        st.project.render.width = r.width.value_or(st.project.render.width);
        st.project.render.height = r.height.value_or(st.project.render.height);
        require(wb.startRender(), "the render could not start (see the log)");
    } else if (what == "wait") {
        if (!waiting_) {
            waiting_ = true;
            waitStart_ = std::chrono::steady_clock::now();
        }
        // train_epoch: until the running training has reported its first epoch (to stop it mid-run).
        // pipeline: until the one-click pipeline has ended; train_running: until a training runs.
        // flip: until the Views' FLIP map of the images on screen has arrived; spread: until the
        // spread map of the prediction on screen has; full_frame: until the draft frames of a light
        // move have been replaced by the full-quality prediction and every job has ended; loads:
        // until what an open, a Compare or a Re-open reads on workers has arrived (models, a run's
        // images, the picking map), the render left running.
        const std::string& on = r.waitFor;
        const bool busy = on == "loads" ? wb.loadsPending()
                          : on == "flip" ? !st.view.flipMap.matches(st.reference().revision, st.compared().revision, st.view.term)
                          : on == "spread"        ? st.view.spread && !st.view.spreadMap.matches(st.prediction.revision)
                          : on == "render"        ? !wb.renderShown()
                          : on == "train_epoch"   ? wb.trainRunning() && st.training.epoch < 1
                          : on == "pipeline"      ? wb.pipelineRunning()
                          : on == "train_running" ? !wb.trainRunning()
                          : on == "full_frame"    ? wb.draftShown() || wb.prediction().bandsPending() || !wb.jobs().drained() ||
                                                        wb.loadsPending() ||
                                                        wb.evaluationPending() || wb.renderRestartPending()
                                                  : !wb.jobs().drained() || wb.evaluationPending() ||
                                                        wb.prediction().bandsPending() || wb.renderRestartPending() ||
                                                        wb.loadsPending() || wb.sweepRunning();
        if (busy) {
            const double limit = r.timeoutSeconds;
            const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - waitStart_).count();
            require(waited < limit, "timed out after " + std::to_string(int(limit)) + " s");
            return false;
        }
    } else if (what == "generate") {
        // Optional overrides of the project's sampling settings, for small scripted datasets: the
        // step's keys are the "sampling" section's, and keys it omits keep their current values.
        if (!r.sampling.empty()) st.project.sampling = samplingOver(r.sampling, st.project.samplingOrDefault());
        require(wb.startGenerate(), "the generator could not start (see the log)");
    } else if (what == "train") {
        // Optional overrides of the project's network settings, for small scripted runs: the step's
        // keys are the "network" section's (omitted keys keep their current values) and "trainer"
        // switches the trainer as the Network panel does.
        if (!r.network.empty()) {
            st.project.network = networkOver(r.network, st.project.networkOrDefault());
            st.markDirty();
        }
        if (r.trainer) {
            st.project.trainer = st.project.trainerOrDefault().withType(*r.trainer);
            st.markDirty();
        }
        // "refused": true expects the workbench to refuse (e.g. no dataset yet) and say why.
        const bool refused = r.refused;
        const bool started = wb.startTrain(r.epochs);
        require(started != refused, refused ? "training started although it should have been refused"
                                            : "training could not start (see the log)");
    } else if (what == "evaluate") {
        require(wb.startEvaluate(), "the evaluation could not start (see the log)");
    } else if (what == "sweep") {
        require(wb.startSweep(r.sweepWhat), "the sweep could not start (see the log)");
    } else if (what == "light_grid") {
        // As setting the Light region panel's grid and clicking "Evaluate over the light region".
        if (r.grid)
            for (int a = 0; a < 3; ++a) st.lightRegion.counts[a] = (*r.grid)[size_t(a)];
        require(wb.startLightGrid(), "the light grid could not start (see the log)");
    } else if (what == "pipeline") {
        // As choosing a preset in the pipeline bar and clicking "Run pipeline" (the request the
        // button makes). Optional sizes shrink the preset for small scripted runs: they are applied
        // over the preset, and the pipeline then runs with the settings in effect.
        // Without "preset": the bar's default, the project's settings unchanged.
        const std::string& name = r.preset;
        if (const PipelinePreset* preset = findPreset(name)) {
            applySamplingPreset(st.project, *preset);
            applyNetworkPreset(st.project, *preset);
        }
        if (!r.sampling.empty()) st.project.sampling = samplingOver(r.sampling, st.project.samplingOrDefault());
        if (!r.network.empty()) st.project.network = networkOver(r.network, st.project.networkOrDefault());
        if (r.pipelineEpochs) {
            TrainerConfig t = st.project.trainerOrDefault();
            const int epochs = *r.pipelineEpochs;
            for (TrainerCommon* c : t.everyTrainer()) c->maxEpochs = epochs;
            st.project.trainer = t;
        }
        st.markDirty();
        require(wb.runPipeline(panels::pipelineChoiceLabel(name)), "the pipeline could not start (see the log)");
    } else if (what == "stop_pipeline") {
        st.request(panels::Command::CancelPipeline);
    } else if (what == "measure_frames") {
        // Records the UI thread's frame times over `frames` frames and prints their median and 95th
        // percentile (bench/bench_frames.sh). drag_light: moves the light a little every frame, as
        // dragging it in the Scene panel does (GLSL prediction and a restarted ground truth).
        if (!waiting_) {
            waiting_ = true;
            framesLeft_ = r.frames;
            dragStart_ = st.project.scene.lightPosition();
            wb.frameStats().startRecording();
        }
        if (r.dragLight) {
            const double a = 0.2 * double(framesLeft_);
            moveLight(st.project, dragStart_ + Vec3(float(0.1 * std::cos(a)), 0.f, float(0.1 * std::sin(a))));
            st.request(panels::Command::SceneChanged);
        }
        if (--framesLeft_ >= 0) return false;
        const FrameTimeSummary f = summarizeFrameTimes(wb.frameStats().takeRecording());
        // With drag_light, how much of a frame the draft prediction itself took (its last frames).
        const FrameTimeSummary p = summarizeFrameTimes(wb.draftSeconds());
        std::printf("frames %-20s median %7.1f ms  p95 %7.1f ms  max %7.1f ms  (%zu frames)%s\n",
                    r.label.c_str(), 1e3 * f.median, 1e3 * f.p95, 1e3 * f.max, f.frames,
                    r.dragLight && p.frames
                        ? ("; draft prediction alone median " + std::to_string(int(1e3 * p.median + 0.5)) + " ms").c_str()
                        : "");
        std::fflush(stdout);
    } else if (what == "tab") {
        st.focusTab = r.tabName;
    } else if (what == "move_tab") {
        // As dragging the tab onto the pane holding `to` (side centre: into it; an edge: split it).
        const std::string &tab = r.moveTab, &to = r.moveTo, &side = r.side;
        const DropSide drop = side == "left"    ? DropSide::Left
                              : side == "right" ? DropSide::Right
                              : side == "top"   ? DropSide::Top
                              : side == "bottom" ? DropSide::Bottom
                                                 : DropSide::Centre;
        require(st.project.layout.moveTab(tab, to, drop), "cannot move tab '" + tab + "' to the pane of '" + to + "'");
    } else if (what == "reset_layout") {
        st.request(panels::Command::ResetLayout);
    } else if (what == "save_run") {
        require(wb.saveRun(), "could not save the run (see the log)");
    } else if (what == "compare_run") {
        require(wb.compareRun(r.index), "could not compare the run (see the log)");
    } else if (what == "reopen_run") {
        require(wb.reopenRun(r.index), "could not re-open the run (see the log)");
    } else if (what == "set_light") {
        const Vec3 position = r.position;
        require(!st.project.scene.lights.empty(), "the scene has no light");
        moveLight(st.project, position);
        st.markDirty();
        st.request(panels::Command::SceneChanged);
    } else if (what == "select_object") {
        st.view.selectedObject = r.objectId;
    } else if (what == "view") {
        if (r.term) st.view.term = *parseTerm(*r.term);
        if (r.metric) {
            // Every error map kind, and "flip" for the Views' FLIP map.
            st.view.flip = *r.metric == "flip";
            if (!st.view.flip) st.view.metric = *parseErrorMapKind(*r.metric);
        }
        st.view.exposure = r.exposure.value_or(st.view.exposure);
        st.view.errorMax = r.errorMax.value_or(st.view.errorMax);
        st.view.zoom = r.zoom.value_or(st.view.zoom);
        st.view.spread = r.spread.value_or(st.view.spread);
        // region: [x0, y0, x1, y1] (x1, y1 exclusive), as a right-drag draws it; [] clears it.
        if (const auto& g = r.region)
            st.view.region = g->empty() ? panels::ViewRegion{} : panels::ViewRegion{(*g)[0], (*g)[1], (*g)[2], (*g)[3]};
    } else if (what == "open") {
        // Without a path: re-open the current project from disk (checks what a save kept).
        const std::string path = r.path.value_or(st.project.path);
        require(wb.openProject(path), "could not open the project (see the log)");
    } else if (what == "request_open") {
        // As File > Open / Recent: asks first when there are unsaved changes.
        wb.requestOpen(r.path.value_or(st.project.path));
    } else if (what == "answer_unsaved") {
        require(wb.unsavedPromptOpen(), "no unsaved-changes prompt is open");
        const std::string& c = r.choice;
        wb.answerUnsavedPrompt(c == "save"      ? Workbench::UnsavedChoice::Save
                               : c == "discard" ? Workbench::UnsavedChoice::Discard
                                                : Workbench::UnsavedChoice::Cancel);
    } else if (what == "compare_runs") {
        // As ticking A and B in the runs table.
        st.runPair.a = r.runA;
        st.runPair.b = r.runB;
        require(wb.compareRunPair(), "could not compare the runs (see the log)");
    } else if (what == "stop") {
        // As the Stop buttons: the job stops at its next check and delivers what it has.
        const std::string& job = r.job;
        st.request(job == "render"     ? panels::Command::CancelRender
                   : job == "generate" ? panels::Command::CancelGenerate
                                       : panels::Command::CancelTrain);
    } else if (what == "save") {
        // A new folder for Save As, as the file dialog would have offered one.
        const std::string path = r.path.value_or("");
        if (!path.empty()) {
            std::error_code ec;
            std::filesystem::create_directories(std::filesystem::absolute(path).parent_path(), ec);
        }
        require(wb.saveProject(path), "could not save (see the log)");
    } else if (what == "export_images") {
        require(wb.exportImages(r.dir), "could not export images (see the log)");
    } else if (what == "screenshot") {
        st.request(panels::Command::ExportScreenshot, r.path.value_or(""));
    } else if (what == "shortcut") {
        // The action of a shortcut of the table (app/gui/shortcuts.h) by its label, as its key does.
        const std::string& keys = r.keys;
        bool found = false;
        for (const Shortcut& shortcut : shortcuts())
            if (keys == shortcut.keys) wb.performShortcut(shortcut.action), found = true;
        if (!found) r.fail("keys", "no shortcut is labelled '" + keys + "'");
    } else if (what == "frames") {
        if (!waiting_) {
            waiting_ = true;
            framesLeft_ = r.frameCount;
        }
        return --framesLeft_ < 0;
    } else if (what == "check") {
        // Each given expectation must hold; counts are compared exactly.
        auto count = [&](const char* key, size_t actual, const std::string& noun) {
            if (const auto v = r.counts.find(key); v != r.counts.end()) {
                const int64_t want = v->second;
                require(int64_t(actual) == want,
                        "expected " + std::to_string(want) + " " + noun + ", found " + std::to_string(actual));
            }
        };
        auto flag = [&](const char* key, bool actual, const std::string& what) {
            if (const auto v = r.flags.find(key); v != r.flags.end()) require(actual == v->second, what + " differs");
        };
        auto want = [&](const char* key) -> std::optional<int64_t> {
            const auto v = r.counts.find(key);
            return v == r.counts.end() ? std::nullopt : std::optional<int64_t>(v->second);
        };
        auto wanted = [&](const char* key) {
            const auto v = r.flags.find(key);
            return v != r.flags.end() && v->second;
        };
        count("runs", st.project.runs.size(), "runs");
        if (const auto v = want("ground_truth_spp_min"))
            require(st.render.spp >= *v,
                    "ground truth has " + std::to_string(st.render.spp) + " spp");
        if (const auto v = want("errors"))
            require(int64_t(st.log.errorCount()) == *v,
                    "the log has " + std::to_string(st.log.errorCount()) + " errors");
        flag("dataset", !st.dataset.path.empty(), "dataset state");
        flag("compare", !st.compare.empty(), "compare view state");
        flag("prediction", !st.prediction.empty(), "prediction view state");
        // prediction_label: text the prediction view's label must contain (e.g. "glossy gather").
        if (const auto& v = r.predictionLabel)
            require(st.prediction.label.find(*v) != std::string::npos,
                    "the prediction's label is \"" + st.prediction.label + "\"");
        // ground_truth_stored: the ground truth shown was loaded from the project's ground_truth/.
        flag("help_open", wb.helpOpen(), "Help window");
        count("undo_steps", wb.settingsHistory().undoSteps(), "undo steps");
        count("redo_steps", wb.settingsHistory().redoSteps(), "redo steps");
        if (const auto& v = r.lightPosition) {
            const Vec3 want = *v, got = st.project.scene.lightPosition();
            require(std::abs(want.x - got.x) < 1e-4f && std::abs(want.y - got.y) < 1e-4f && std::abs(want.z - got.z) < 1e-4f,
                    "the light is at (" + std::to_string(got.x) + ", " + std::to_string(got.y) + ", " + std::to_string(got.z) + ")");
        }
        count("status_idle_while_pipeline", size_t(wb.statusIdleWhilePipeline()), "status-bar frames idle during the pipeline");
        flag("ground_truth_stored", st.groundTruth.label == kStoredGroundTruthLabel, "stored ground truth");
        // error_waiting: the Views withhold their error figures until a ground truth of this light.
        flag("error_waiting", !st.view.errorStats.waiting.empty(), "error figures' waiting state");
        count("sweeps", st.cost.sweeps.size(), "sweeps");
        flag("evaluated", st.evaluation.valid, "evaluation state");
        // objects_rows: the Objects table's rows (global term) of the evaluation shown.
        count("objects_rows", st.evaluation.valid ? st.evaluation.rows[int(Term::Global)].size() : 0, "Objects table rows");
        // full_frame_banded: the last full-quality GLSL frame was not rendered in one go on the UI
        // thread unless it was cheap: more than one band, or device time within a band's budget
        // (a fast GPU). Structure, not a frame time: robust on a loaded machine.
        if (wanted("full_frame_banded")) {
            const auto& f = wb.prediction().lastFullFrame();
            require(f.bands > 0, "no full-quality GLSL frame was shown");
            require(f.bands > 1 || f.gpuSeconds <= kBandBudgetSeconds,
                    "the full frame (" + std::to_string(f.gpuSeconds) + " s on the device) was rendered in one band");
        }
        // uploads_announced: every model set uploaded so far (compiling shaders on the UI thread)
        // came after a frame whose status bar said so, and there was at least one.
        if (wanted("uploads_announced")) {
            const PredictionController& p = wb.prediction();
            require(p.uploads() > 0, "no model set was uploaded");
            require(p.announcedUploads() == p.uploads(), std::to_string(p.uploads() - p.announcedUploads()) + " of " +
                                                             std::to_string(p.uploads()) + " model uploads came without a note");
        }
        // programs_cached: the GLSL programs of the last model load came from the program binary
        // cache (app/gl/program_binary_cache.h), none compiled; passes with a note where the driver
        // offers no binary format (the cache is then a no-op by design).
        if (wanted("programs_cached")) {
            const ProgramBinaryCache::Counts c = wb.prediction().lastLoadPrograms();
            if (c.hits + c.misses == 0)
                st.log.info("check programs_cached: the driver offers no program binary format; nothing to check");
            else
                require(c.hits > 0 && c.misses == 0, "the last model load compiled " + std::to_string(c.misses) +
                                                         " GLSL program(s); " + std::to_string(c.hits) + " came from the binary cache");
        }
        // longest_frame_ms_max: no UI frame since the first took longer (issue 29: no stall at
        // open, train end or reopen; the GL worker compiles the prediction's shaders).
        if (const auto v = want("longest_frame_ms_max"))
            require(wb.frameStats().longestAfterFirst() * 1e3 <= double(*v),
                    "a UI frame took " + std::to_string(int(wb.frameStats().longestAfterFirst() * 1e3 + 0.5)) + " ms");
        // region_pixels_min: the Views' region has figures over at least this many pixels.
        if (const auto v = want("region_pixels_min"))
            require(st.view.regionStats.valid && st.view.regionStats.stats.pixels >= uint64_t(*v),
                    "the region has figures over " + std::to_string(st.view.regionStats.valid ? st.view.regionStats.stats.pixels : 0) +
                        " pixels");
        // light_grid_points: the Light region panel's map has this many light positions.
        count("light_grid_points", st.lightRegion.map ? st.lightRegion.map->lights.size() : 0, "light grid points");
        // flip_evaluated: the last evaluation has FLIP figures (global term, finite mean).
        flag("flip_evaluated", st.evaluation.valid && std::isfinite(st.evaluation.flipHdr), "evaluation's FLIP state");
        // spread_shown: the middle view shows the ensemble spread map (with pixels that have one);
        // spread_evaluated: the last evaluation ranked the spread against the error (finite Spearman).
        flag("spread_shown", panels::spreadShown(st) && st.view.spreadMap.pixels > 0, "spread view state");
        flag("spread_evaluated", st.evaluation.valid && std::isfinite(st.evaluation.spreadSpearman), "evaluation's spread state");
        size_t trained = 0;
        for (const Run& run : st.project.runs) trained += run.kind == "train" && !run.curves.empty();
        count("train_runs", trained, "training runs with loss curves");
        size_t stopped = 0;
        for (const Run& run : st.project.runs) stopped += isStoppedTrainRun(run);
        count("stopped_runs", stopped, "stopped training runs");
        flag("unsaved_prompt", wb.unsavedPromptOpen(), "unsaved-changes prompt state");
        flag("dirty", st.dirty, "unsaved-changes state");
        flag("prediction_partial", !st.prediction.withoutNetwork.empty(), "partial prediction state");
        flag("render_cancelled", st.render.cancelled, "render cancelled state");
        flag("notice", st.notice.has_value(), "notice state");
        count("panes", st.project.layout.panes().size(), "panes");
        // clipped: how many windows, table columns and fitted widgets cut their text off this frame.
        if (const auto clipped = want("clipped")) {
            const std::vector<panels::ClippedContent> found = panels::findClippedContent();
            const int64_t want = *clipped;
            std::string list;
            for (const panels::ClippedContent& c : found) list += "\n  " + c.describe();
            require(int64_t(found.size()) == want, "expected " + std::to_string(want) + " clipped texts, found " +
                                                       std::to_string(found.size()) + list);
        }
        // same_pane: [a, b] must be tabs of one pane.
        if (const auto& pair = r.samePane) {
            const PaneNode* a = st.project.layout.paneOf(pair->first);
            const PaneNode* b = st.project.layout.paneOf(pair->second);
            require(a && b, "a tab named in same_pane is in no pane");
            require(a == b, "'" + pair->first + "' and '" + pair->second + "' are in different panes");
        }
        // pipeline_done: the last one-click pipeline ran to its end (not stopped, not failed).
        flag("pipeline_done", !wb.pipelineRunning() && st.pipeline.outcome.rfind("done", 0) == 0,
             "pipeline outcome ('" + st.pipeline.outcome + "')");
        flag("pipeline_stopped", !wb.pipelineRunning() && st.pipeline.outcome.rfind("stopped", 0) == 0,
             "pipeline outcome ('" + st.pipeline.outcome + "')");
        // pair: the Views show two runs (both predictions) and the Objects panel both error columns.
        flag("pair",
             st.view.compareSource == panels::CompareSource::RunPair && !st.runPair.imagesA.empty() &&
                 !st.runPair.imagesB.empty() && st.runPair.errorsA.valid && st.runPair.errorsB.valid,
             "run pair state");
    } else {
        throw std::runtime_error("unknown step '" + what + "'");
    }
    return true;
}

}  // namespace rrf
