#include "app/gui/script.h"

#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "app/gui/workbench.h"
#include "core/nn/network_settings.h"
#include "core/project/scene_edits.h"
#include "core/util/json_reader.h"

namespace rrf {

using nlohmann::json;

namespace {
/// The keys each step may have besides "do"; a step not listed here is unknown.
const std::map<std::string, std::vector<const char*>>& stepKeys() {
    static const std::map<std::string, std::vector<const char*>> keys = {
        {"render", {"spp"}},
        {"generate", {"grid", "dirs", "spp"}},
        {"train", {"epochs", "hidden", "trainer", "targets"}},
        {"evaluate", {}},
        {"sweep", {"what"}},
        {"wait", {"for", "timeout_s"}},
        {"save_run", {}},
        {"compare_run", {"index"}},
        {"reopen_run", {"index"}},
        {"set_light", {"position"}},
        {"select_object", {"id"}},
        {"view", {"term", "metric", "exposure", "error_max", "zoom"}},
        {"open", {"path"}},
        {"save", {"path"}},
        {"export_images", {"dir"}},
        {"screenshot", {"path"}},
        {"frames", {"count"}},
        {"tab", {"name"}},
        {"check", {"runs", "ground_truth_spp_min", "errors", "compare", "dataset", "prediction", "evaluated",
                   "train_runs", "sweeps"}},
    };
    return keys;
}

/// Rejects keys the step does not take (checkKeys with a run-time list).
void checkStepKeys(const JsonReader& step, const std::vector<const char*>& allowed) {
    for (auto it = step.value().begin(); it != step.value().end(); ++it) {
        if (it.key() == "do") continue;
        bool known = false;
        for (const char* a : allowed) known = known || it.key() == a;
        if (known) continue;
        std::string list = "do";
        for (const char* a : allowed) list += std::string(", ") + a;
        throw InputError(step.file(), JsonReader::child(step.pointer(), it.key()),
                         "unknown key '" + it.key() + "' (allowed here: " + list + ")");
    }
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
            checkStepKeys(step, keys->second);
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
        require(wb.startRender(), "the render could not start (see the log)");
    } else if (what == "wait") {
        if (!waiting_) {
            waiting_ = true;
            waitStart_ = std::chrono::steady_clock::now();
        }
        const std::string on = r.choiceOr("for", "jobs", {"render", "jobs"});
        const bool busy = on == "render" ? wb.renderRunning() : !wb.jobs().idle();
        if (busy) {
            const double limit = r.numberOr("timeout_s", 300, 0, 1e9);
            const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - waitStart_).count();
            require(waited < limit, "timed out after " + std::to_string(int(limit)) + " s");
            return false;
        }
    } else if (what == "generate") {
        // Optional overrides of the project's sampling settings, for small scripted datasets.
        if (r.has("grid") || r.has("dirs") || r.has("spp")) {
            SamplingSettings sampling = st.project.samplingOrDefault();
            if (const auto grid = r.find("grid")) {
                if (grid->requireArray() != 3) grid->fail("expected [nx, ny, nz]");
                int* dims[] = {&sampling.nx, &sampling.ny, &sampling.nz};
                for (size_t i = 0; i < 3; ++i) *dims[i] = int(grid->at(i).integer(1, 1000));
            }
            sampling.directions = int(r.integerOr("dirs", sampling.directions, 1, 10000000));
            sampling.spp = int(r.integerOr("spp", sampling.spp, 1, 1000000));
            st.project.sampling = sampling;
        }
        require(wb.startGenerate(), "the generator could not start (see the log)");
    } else if (what == "train") {
        // Optional overrides of the project's network settings, for small scripted runs.
        if (r.has("hidden") || r.has("trainer") || r.has("targets")) {
            NetworkSettings n = st.project.networkOrDefault();
            if (const auto hidden = r.find("hidden")) {
                if (hidden->requireArray() == 0) hidden->fail("expected a non-empty array of layer sizes");
                n.options.hidden.clear();
                for (size_t i = 0; i < hidden->value().size(); ++i)
                    n.options.hidden.push_back(int(hidden->at(i).integer(1, 4096)));
            }
            n.options.targets = parseTargetMode(r.choiceOr("targets", targetModeName(n.options.targets),
                                                           {"separate", "joint", "global", "direct", "indirect"}));
            if (r.has("trainer")) {
                // The named trainer with its defaults, as a project section {"type": name} gives.
                const std::string type = r.choiceOr("trainer", "", {"levenberg_marquardt", "lm", "adam"});
                n.options.trainer = TrainerConfig();
                n.options.trainer.type = type == "adam" ? TrainerType::Adam : TrainerType::LevenbergMarquardt;
            }
            st.project.network = n;
            st.markDirty();
        }
        require(wb.startTrain(intOr(r, "epochs", 0)), "training could not start (see the log)");
    } else if (what == "evaluate") {
        require(wb.startEvaluate(), "the evaluation could not start (see the log)");
    } else if (what == "sweep") {
        require(wb.startSweep(r.at("what").string()), "the sweep could not start (see the log)");
    } else if (what == "tab") {
        st.focusTab = r.at("name").string();
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
            const std::string m = r.choiceOr("metric", "", {"absolute", "relative", "squared"});
            st.view.metric = *parseErrorMapKind(m);
        }
        st.view.exposure = r.floatOr("exposure", st.view.exposure);
        st.view.errorMax = r.floatOr("error_max", st.view.errorMax);
        st.view.zoom = r.floatOr("zoom", st.view.zoom);
    } else if (what == "open") {
        // Without a path: re-open the current project from disk (checks what a save kept).
        const std::string path = r.stringOr("path", st.project.path);
        require(wb.openProject(path), "could not open the project (see the log)");
    } else if (what == "save") {
        require(wb.saveProject(r.stringOr("path", "")), "could not save (see the log)");
    } else if (what == "export_images") {
        require(wb.exportImages(r.at("dir").string()), "could not export images (see the log)");
    } else if (what == "screenshot") {
        st.request(panels::Command::ExportScreenshot, r.at("path").string());
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
        count("sweeps", st.cost.sweeps.size(), "sweeps");
        flag("evaluated", st.evaluation.valid, "evaluation state");
        size_t trained = 0;
        for (const Run& run : st.project.runs) trained += run.kind == "train" && !run.curves.empty();
        count("train_runs", trained, "training runs with loss curves");
    } else {
        throw std::runtime_error("unknown step '" + what + "'");
    }
    return true;
}

}  // namespace rrf
