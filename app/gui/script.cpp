#include "app/gui/script.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
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
#include "core/util/json_reader.h"
#include "panels/clip_check.h"
#include "panels/pipeline_controls.h"
#include "panels/view_model.h"

namespace rrf {

using nlohmann::json;

namespace {
/// The keys each step may have besides "do"; a step not listed here is unknown. generate and train
/// take the project's own "sampling" and "network" keys (read by the same readers).
const std::map<std::string, std::vector<std::string>>& stepKeys() {
    static const std::map<std::string, std::vector<std::string>> keys = [] {
        std::vector<std::string> train = {"epochs", "trainer", "refused"};
        train.insert(train.end(), NetworkSettings::keys().begin(), NetworkSettings::keys().end());
        return std::map<std::string, std::vector<std::string>>{
            {"render", {"spp", "width", "height"}},
            {"generate", SamplingSettings::keys()},
            {"train", train},
            {"evaluate", {}},
            {"sweep", {"what"}},
            {"light_grid", {"grid"}},
            {"wait", {"for", "timeout_s"}},
            {"save_run", {}},
            {"compare_run", {"index"}},
            {"reopen_run", {"index"}},
            {"set_light", {"position"}},
            {"select_object", {"id"}},
            {"view", {"term", "metric", "exposure", "error_max", "zoom", "region", "spread"}},
            {"open", {"path"}},
            {"request_open", {"path"}},
            {"answer_unsaved", {"choice"}},
            {"stop", {"job"}},
            {"compare_runs", {"a", "b"}},
            {"save", {"path"}},
            {"export_images", {"dir"}},
            {"screenshot", {"path"}},
            {"frames", {"count"}},
            {"shortcut", {"keys"}},
            {"tab", {"name"}},
            {"move_tab", {"tab", "to", "side"}},
            {"reset_layout", {}},
            {"pipeline", {"preset", "grid", "directions", "spp", "max_spp", "epochs", "hidden"}},
            {"stop_pipeline", {}},
            {"measure_frames", {"label", "frames", "drag_light"}},
            {"check", {"runs", "ground_truth_spp_min", "errors", "compare", "dataset", "prediction", "evaluated",
                       "train_runs", "sweeps", "unsaved_prompt", "dirty", "stopped_runs", "prediction_partial",
                       "render_cancelled", "notice", "pair", "panes", "same_pane", "clipped", "pipeline_done",
                       "pipeline_stopped", "prediction_label", "error_waiting", "flip_evaluated",
                       "region_pixels_min", "light_grid_points", "spread_shown", "spread_evaluated",
                       "ground_truth_stored", "help_open", "status_idle_while_pipeline",
                       "undo_steps", "redo_steps", "light_position", "objects_rows", "programs_cached",
                       "full_frame_banded", "uploads_announced"}},
        };
    }();
    return keys;
}

/// The step without "do" and `also`: the settings section it carries, at the step's own JSON pointer.
json sectionOf(const JsonReader& step, std::initializer_list<const char*> also) {
    json section = step.value();
    section.erase("do");
    for (const char* key : also) section.erase(key);
    return section;
}

int intOr(const JsonReader& s, const char* key, int fallback) {
    return int(s.integerOr(key, fallback, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}
}  // namespace

bool Script::load(const std::string& path, std::string& error) {
    try {
        steps_ = readJsonFile(path);
        file_ = path;
        const JsonReader root(steps_, path);
        if (!root.isArray()) root.fail("a script is a JSON array of steps, got " + JsonReader::describe(steps_));
        for (size_t i = 0; i < steps_.size(); ++i) {
            const JsonReader step = root.at(i);
            const std::string what = step.at("do").string();
            const auto keys = stepKeys().find(what);
            if (keys == stepKeys().end()) step.at("do").fail("unknown step '" + what + "'");
            std::vector<std::string> allowed = {"do"};
            allowed.insert(allowed.end(), keys->second.begin(), keys->second.end());
            step.checkKeys(allowed);
        }
    } catch (const InputError& e) {
        error = e.what();
        steps_ = json::array();
        return false;
    }
    return true;
}

Script::Status Script::fail(const std::string& message) {
    failed_ = true;
    error_ = "script step " + std::to_string(next_) + " (" + steps_[next_].value("do", std::string()) + "): " + message;
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

bool Script::execute(Workbench& wb, const json& s) {
    panels::WorkbenchState& st = wb.state();
    const JsonReader r(s, file_, "/" + std::to_string(next_));
    const std::string what = r.at("do").string();
    auto require = [](bool ok, const std::string& message) {
        if (!ok) throw std::runtime_error(message);
    };

    if (what == "render") {
        // Replaces the running render (e.g. the one started on open): stop it, wait, then start.
        if (wb.renderRunning()) {
            wb.cancelRender();
            return false;
        }
        st.project.render.spp = int(r.integerOr("spp", st.project.render.spp, 1, 1 << 30));
        // The image size as the project's "render" section takes it (0: the scene camera's).
        st.project.render.width = int(r.integerOr("width", st.project.render.width, 0, kMaxImageSide));
        st.project.render.height = int(r.integerOr("height", st.project.render.height, 0, kMaxImageSide));
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
        const std::string on =
            r.choiceOr("for", "jobs", {"render", "jobs", "train_epoch", "pipeline", "train_running", "flip", "spread", "full_frame", "loads"});
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
                                                        wb.loadsPending();
        if (busy) {
            const double limit = r.numberOr("timeout_s", 300, 0, 1e9);
            const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - waitStart_).count();
            require(waited < limit, "timed out after " + std::to_string(int(limit)) + " s");
            return false;
        }
    } else if (what == "generate") {
        // Optional overrides of the project's sampling settings, for small scripted datasets: the
        // step's keys are the "sampling" section's, and keys it omits keep their current values.
        const json section = sectionOf(r, {});
        if (!section.empty())
            st.project.sampling = SamplingSettings::fromJson(JsonReader(section, r.file(), r.pointer()),
                                                             st.project.samplingOrDefault());
        require(wb.startGenerate(), "the generator could not start (see the log)");
    } else if (what == "train") {
        // Optional overrides of the project's network settings, for small scripted runs: the step's
        // keys are the "network" section's (omitted keys keep their current values) and "trainer"
        // switches the trainer as the Network panel does.
        const json section = sectionOf(r, {"epochs", "trainer", "refused"});
        if (!section.empty()) {
            st.project.network = NetworkSettings::fromJson(JsonReader(section, r.file(), r.pointer()),
                                                           st.project.networkOrDefault());
            st.markDirty();
        }
        if (r.has("trainer")) {
            const std::string type = r.choiceOr("trainer", "", trainerTypeNames());
            st.project.trainer = st.project.trainerOrDefault().withType(type);
            st.markDirty();
        }
        // "refused": true expects the workbench to refuse (e.g. no dataset yet) and say why.
        const bool refused = r.booleanOr("refused", false);
        const bool started = wb.startTrain(intOr(r, "epochs", 0));
        require(started != refused, refused ? "training started although it should have been refused"
                                            : "training could not start (see the log)");
    } else if (what == "evaluate") {
        require(wb.startEvaluate(), "the evaluation could not start (see the log)");
    } else if (what == "sweep") {
        require(wb.startSweep(r.at("what").string()), "the sweep could not start (see the log)");
    } else if (what == "light_grid") {
        // As setting the Light region panel's grid and clicking "Evaluate over the light region".
        if (r.has("grid")) {
            const JsonReader g = r.at("grid");
            for (int a = 0; a < 3; ++a)
                st.lightRegion.counts[a] = int(g.at(size_t(a)).integer(1, panels::LightRegionInfo::kMaxCount));
        }
        require(wb.startLightGrid(), "the light grid could not start (see the log)");
    } else if (what == "pipeline") {
        // As choosing a preset in the pipeline bar and clicking "Run pipeline" (the request the
        // button makes). Optional sizes shrink the preset for small scripted runs: they are applied
        // over the preset, and the pipeline then runs with the settings in effect.
        // Without "preset": the bar's default, the project's settings unchanged.
        const std::string name = r.has("preset") ? r.choiceOr("preset", "", {"quick", "paper", "default", "best"}) : "";
        if (const PipelinePreset* preset = findPreset(name)) {
            applySamplingPreset(st.project, *preset);
            applyNetworkPreset(st.project, *preset);
        }
        json sampling = sectionOf(r, {"preset", "epochs", "hidden"});
        if (!sampling.empty())
            st.project.sampling = SamplingSettings::fromJson(JsonReader(sampling, r.file(), r.pointer()),
                                                             st.project.samplingOrDefault());
        if (r.has("hidden")) {
            const json network = {{"hidden", r.at("hidden").value()}};
            st.project.network =
                NetworkSettings::fromJson(JsonReader(network, r.file(), r.pointer()), st.project.networkOrDefault());
        }
        if (r.has("epochs")) {
            TrainerConfig t = st.project.trainerOrDefault();
            const int epochs = intOr(r, "epochs", 1);
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
            framesLeft_ = intOr(r, "frames", 60);
            dragStart_ = st.project.scene.lightPosition();
            wb.frameStats().startRecording();
        }
        if (r.booleanOr("drag_light", false)) {
            const double a = 0.2 * double(framesLeft_);
            moveLight(st.project, dragStart_ + Vec3(float(0.1 * std::cos(a)), 0.f, float(0.1 * std::sin(a))));
            st.request(panels::Command::SceneChanged);
        }
        if (--framesLeft_ >= 0) return false;
        const FrameTimeSummary f = summarizeFrameTimes(wb.frameStats().takeRecording());
        // With drag_light, how much of a frame the draft prediction itself took (its last frames).
        const FrameTimeSummary p = summarizeFrameTimes(wb.draftSeconds());
        std::printf("frames %-20s median %7.1f ms  p95 %7.1f ms  max %7.1f ms  (%zu frames)%s\n",
                    r.stringOr("label", "").c_str(), 1e3 * f.median, 1e3 * f.p95, 1e3 * f.max, f.frames,
                    r.booleanOr("drag_light", false) && p.frames
                        ? ("; draft prediction alone median " + std::to_string(int(1e3 * p.median + 0.5)) + " ms").c_str()
                        : "");
        std::fflush(stdout);
    } else if (what == "tab") {
        st.focusTab = r.at("name").string();
    } else if (what == "move_tab") {
        // As dragging the tab onto the pane holding `to` (side centre: into it; an edge: split it).
        const std::string tab = r.at("tab").string(), to = r.at("to").string();
        const std::string side = r.choiceOr("side", "centre", {"centre", "left", "right", "top", "bottom"});
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
        require(wb.compareRun(intOr(r, "index", 0)), "could not compare the run (see the log)");
    } else if (what == "reopen_run") {
        require(wb.reopenRun(intOr(r, "index", 0)), "could not re-open the run (see the log)");
    } else if (what == "set_light") {
        const Vec3 position = r.at("position").vec3();
        require(!st.project.scene.lights.empty(), "the scene has no light");
        moveLight(st.project, position);
        st.markDirty();
        st.request(panels::Command::SceneChanged);
    } else if (what == "select_object") {
        st.view.selectedObject = intOr(r, "id", -1);
    } else if (what == "view") {
        if (r.has("term")) {
            const std::string t = r.choiceOr("term", "", {"global", "direct", "indirect"});
            st.view.term = *parseTerm(t);
        }
        if (r.has("metric")) {
            // Every error map kind, and "flip" for the Views' FLIP map.
            static_assert(std::size(kErrorMapKinds) == 6, "every error map kind is a script choice");
            const std::string m = r.choiceOr("metric", "", {errorMapName(kErrorMapKinds[0]), errorMapName(kErrorMapKinds[1]),
                                                            errorMapName(kErrorMapKinds[2]), errorMapName(kErrorMapKinds[3]),
                                                            errorMapName(kErrorMapKinds[4]), errorMapName(kErrorMapKinds[5]), "flip"});
            st.view.flip = m == "flip";
            if (!st.view.flip) st.view.metric = *parseErrorMapKind(m);
        }
        st.view.exposure = r.floatOr("exposure", st.view.exposure);
        st.view.errorMax = r.floatOr("error_max", st.view.errorMax);
        st.view.zoom = r.floatOr("zoom", st.view.zoom);
        st.view.spread = r.booleanOr("spread", st.view.spread);
        // region: [x0, y0, x1, y1] (x1, y1 exclusive), as a right-drag draws it; [] clears it.
        if (const auto g = r.find("region")) {
            const size_t n = g->requireArray();
            if (n != 0 && n != 4) g->fail("expected [x0, y0, x1, y1] or []");
            st.view.region = n == 0 ? panels::ViewRegion{}
                                    : panels::ViewRegion{int(g->at(size_t(0)).integer(0, 1 << 20)), int(g->at(size_t(1)).integer(0, 1 << 20)),
                                                         int(g->at(size_t(2)).integer(0, 1 << 20)), int(g->at(size_t(3)).integer(0, 1 << 20))};
        }
    } else if (what == "open") {
        // Without a path: re-open the current project from disk (checks what a save kept).
        const std::string path = r.stringOr("path", st.project.path);
        require(wb.openProject(path), "could not open the project (see the log)");
    } else if (what == "request_open") {
        // As File > Open / Recent: asks first when there are unsaved changes.
        wb.requestOpen(r.stringOr("path", st.project.path));
    } else if (what == "answer_unsaved") {
        require(wb.unsavedPromptOpen(), "no unsaved-changes prompt is open");
        const std::string c = r.choiceOr("choice", "", {"save", "discard", "cancel"});
        wb.answerUnsavedPrompt(c == "save"      ? Workbench::UnsavedChoice::Save
                               : c == "discard" ? Workbench::UnsavedChoice::Discard
                                                : Workbench::UnsavedChoice::Cancel);
    } else if (what == "compare_runs") {
        // As ticking A and B in the runs table.
        st.runPair.a = intOr(r, "a", 0);
        st.runPair.b = intOr(r, "b", 1);
        require(wb.compareRunPair(), "could not compare the runs (see the log)");
    } else if (what == "stop") {
        // As the Stop buttons: the job stops at its next check and delivers what it has.
        const std::string job = r.choiceOr("job", "", {"render", "generate", "train"});
        st.request(job == "render"     ? panels::Command::CancelRender
                   : job == "generate" ? panels::Command::CancelGenerate
                                       : panels::Command::CancelTrain);
    } else if (what == "save") {
        // A new folder for Save As, as the file dialog would have offered one.
        const std::string path = r.stringOr("path", "");
        if (!path.empty()) {
            std::error_code ec;
            std::filesystem::create_directories(std::filesystem::absolute(path).parent_path(), ec);
        }
        require(wb.saveProject(path), "could not save (see the log)");
    } else if (what == "export_images") {
        require(wb.exportImages(r.at("dir").string()), "could not export images (see the log)");
    } else if (what == "screenshot") {
        st.request(panels::Command::ExportScreenshot, r.at("path").string());
    } else if (what == "shortcut") {
        // The action of a shortcut of the table (app/gui/shortcuts.h) by its label, as its key does.
        const std::string keys = r.at("keys").string();
        bool found = false;
        for (const Shortcut& shortcut : shortcuts())
            if (keys == shortcut.keys) wb.performShortcut(shortcut.action), found = true;
        if (!found) r.at("keys").fail("no shortcut is labelled '" + keys + "'");
    } else if (what == "frames") {
        if (!waiting_) {
            waiting_ = true;
            framesLeft_ = intOr(r, "count", 1);
        }
        return --framesLeft_ < 0;
    } else if (what == "check") {
        // Each given expectation must hold; counts are compared exactly.
        auto count = [&](const char* key, size_t actual, const std::string& noun) {
            if (const auto v = r.find(key)) {
                const int64_t want = v->integer(0, std::numeric_limits<int>::max());
                require(int64_t(actual) == want,
                        "expected " + std::to_string(want) + " " + noun + ", found " + std::to_string(actual));
            }
        };
        auto flag = [&](const char* key, bool actual, const std::string& what) {
            if (const auto v = r.find(key)) require(actual == v->boolean(), what + " differs");
        };
        count("runs", st.project.runs.size(), "runs");
        if (const auto v = r.find("ground_truth_spp_min"))
            require(st.render.spp >= v->integer(0, std::numeric_limits<int>::max()),
                    "ground truth has " + std::to_string(st.render.spp) + " spp");
        if (const auto v = r.find("errors"))
            require(int64_t(st.log.errorCount()) == v->integer(0, std::numeric_limits<int>::max()),
                    "the log has " + std::to_string(st.log.errorCount()) + " errors");
        flag("dataset", !st.dataset.path.empty(), "dataset state");
        flag("compare", !st.compare.empty(), "compare view state");
        flag("prediction", !st.prediction.empty(), "prediction view state");
        // prediction_label: text the prediction view's label must contain (e.g. "glossy gather").
        if (const auto v = r.find("prediction_label"))
            require(st.prediction.label.find(v->string()) != std::string::npos,
                    "the prediction's label is \"" + st.prediction.label + "\"");
        // ground_truth_stored: the ground truth shown was loaded from the project's ground_truth/.
        flag("help_open", wb.helpOpen(), "Help window");
        count("undo_steps", wb.settingsHistory().undoSteps(), "undo steps");
        count("redo_steps", wb.settingsHistory().redoSteps(), "redo steps");
        if (const auto v = r.find("light_position")) {
            const Vec3 want = v->vec3(), got = st.project.scene.lightPosition();
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
        if (const auto v = r.find("full_frame_banded"); v && v->boolean()) {
            const auto& f = wb.prediction().lastFullFrame();
            require(f.bands > 0, "no full-quality GLSL frame was shown");
            require(f.bands > 1 || f.gpuSeconds <= kBandBudgetSeconds,
                    "the full frame (" + std::to_string(f.gpuSeconds) + " s on the device) was rendered in one band");
        }
        // uploads_announced: every model set uploaded so far (compiling shaders on the UI thread)
        // came after a frame whose status bar said so, and there was at least one.
        if (const auto v = r.find("uploads_announced"); v && v->boolean()) {
            const PredictionController& p = wb.prediction();
            require(p.uploads() > 0, "no model set was uploaded");
            require(p.announcedUploads() == p.uploads(), std::to_string(p.uploads() - p.announcedUploads()) + " of " +
                                                             std::to_string(p.uploads()) + " model uploads came without a note");
        }
        // programs_cached: the GLSL programs of the last model load came from the program binary
        // cache (app/gl/program_binary_cache.h), none compiled; passes with a note where the driver
        // offers no binary format (the cache is then a no-op by design).
        if (const auto v = r.find("programs_cached"); v && v->boolean()) {
            const ProgramBinaryCache::Counts c = wb.prediction().lastLoadPrograms();
            if (c.hits + c.misses == 0)
                st.log.info("check programs_cached: the driver offers no program binary format; nothing to check");
            else
                require(c.hits > 0 && c.misses == 0, "the last model load compiled " + std::to_string(c.misses) +
                                                         " GLSL program(s); " + std::to_string(c.hits) + " came from the binary cache");
        }
        // region_pixels_min: the Views' region has figures over at least this many pixels.
        if (const auto v = r.find("region_pixels_min"))
            require(st.view.regionStats.valid && st.view.regionStats.stats.pixels >= uint64_t(v->integer(0, std::numeric_limits<int>::max())),
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
        if (const auto v = r.find("clipped")) {
            const std::vector<panels::ClippedContent> found = panels::findClippedContent();
            const int64_t want = v->integer(0, std::numeric_limits<int>::max());
            std::string list;
            for (const panels::ClippedContent& c : found) list += "\n  " + c.describe();
            require(int64_t(found.size()) == want, "expected " + std::to_string(want) + " clipped texts, found " +
                                                       std::to_string(found.size()) + list);
        }
        // same_pane: [a, b] must be tabs of one pane.
        if (const auto v = r.find("same_pane")) {
            const JsonReader pair = *v;
            if (pair.requireArray() != 2) pair.fail("expected an array of 2 tab names");
            const PaneNode* a = st.project.layout.paneOf(pair.at(size_t(0)).string());
            const PaneNode* b = st.project.layout.paneOf(pair.at(size_t(1)).string());
            require(a && b, "a tab named in same_pane is in no pane");
            require(a == b, "'" + pair.at(size_t(0)).string() + "' and '" + pair.at(size_t(1)).string() +
                                "' are in different panes");
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
