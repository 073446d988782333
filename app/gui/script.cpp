#include "app/gui/script.h"

#include <fstream>
#include <stdexcept>

#include "app/gui/workbench.h"
#include "core/nn/network_settings.h"
#include "core/project/scene_overrides.h"

namespace rrf {

using nlohmann::json;

namespace {
double number(const json& s, const char* key, double fallback) {
    if (!s.contains(key)) return fallback;
    if (!s[key].is_number()) throw std::invalid_argument(std::string("'") + key + "' must be a number");
    return s[key].get<double>();
}

std::string text(const json& s, const char* key) {
    if (!s.contains(key) || !s[key].is_string()) throw std::invalid_argument(std::string("needs a string '") + key + "'");
    return s[key].get<std::string>();
}
}  // namespace

bool Script::load(const std::string& path, std::string& error) {
    std::ifstream in(path);
    if (!in) {
        error = path + ": cannot open the script";
        return false;
    }
    try {
        steps_ = json::parse(in);
    } catch (const std::exception& e) {
        error = path + ": " + e.what();
        return false;
    }
    if (!steps_.is_array()) {
        error = path + ": a script is a JSON array of steps";
        return false;
    }
    for (size_t i = 0; i < steps_.size(); ++i) {
        if (!steps_[i].is_object() || !steps_[i].contains("do") || !steps_[i]["do"].is_string()) {
            error = path + ": step " + std::to_string(i) + " needs a \"do\" string";
            return false;
        }
    }
    return true;
}

Script::Status Script::fail(const std::string& message) {
    failed_ = true;
    error_ = "script step " + std::to_string(next_) + " (" + steps_[next_]["do"].get<std::string>() + "): " + message;
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
    const std::string what = s["do"].get<std::string>();
    auto require = [](bool ok, const std::string& message) {
        if (!ok) throw std::runtime_error(message);
    };

    if (what == "render") {
        // Replaces the running render (e.g. the one started on open): stop it, wait, then start.
        if (wb.renderRunning()) {
            wb.cancelRender();
            return false;
        }
        if (s.contains("spp")) st.project.render.spp = int(number(s, "spp", 1));
        require(wb.startRender(), "the render could not start (see the log)");
    } else if (what == "wait") {
        if (!waiting_) {
            waiting_ = true;
            waitStart_ = std::chrono::steady_clock::now();
        }
        const std::string on = s.contains("for") ? text(s, "for") : "jobs";
        require(on == "render" || on == "jobs", "'for' must be \"render\" or \"jobs\"");
        const bool busy = on == "render" ? wb.renderRunning() : !wb.jobs().idle();
        if (busy) {
            const double limit = number(s, "timeout_s", 300);
            const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - waitStart_).count();
            require(waited < limit, "timed out after " + std::to_string(int(limit)) + " s");
            return false;
        }
    } else if (what == "generate") {
        // Optional overrides of the project's sampling settings, for small scripted datasets.
        nlohmann::json sampling = st.project.doc.contains("sampling") ? st.project.doc["sampling"] : json::object();
        if (s.contains("grid")) sampling["grid"] = s["grid"];
        if (s.contains("dirs")) sampling["directions"] = s["dirs"];
        if (s.contains("spp")) sampling["spp"] = s["spp"];
        st.project.doc["sampling"] = sampling;
        require(wb.startGenerate(), "the generator could not start (see the log)");
    } else if (what == "train") {
        // Optional overrides of the project's network settings, for small scripted runs.
        if (s.contains("hidden") || s.contains("trainer") || s.contains("targets")) {
            NetworkSettings n = networkSettingsOf(st.project);
            if (s.contains("hidden")) n.options.hidden = s["hidden"].get<std::vector<int>>();
            if (s.contains("targets")) n.options.targets = parseTargetMode(text(s, "targets"));
            if (s.contains("trainer")) n.options.trainer = TrainerConfig::fromJson(json{{"type", text(s, "trainer")}}, "script");
            storeNetworkSettings(n, st.project);
            st.markDirty();
        }
        require(wb.startTrain(int(number(s, "epochs", 0))), "training could not start (see the log)");
    } else if (what == "evaluate") {
        require(wb.startEvaluate(), "the evaluation could not start (see the log)");
    } else if (what == "sweep") {
        require(wb.startSweep(text(s, "what")), "the sweep could not start (see the log)");
    } else if (what == "tab") {
        st.focusTab = text(s, "name");
    } else if (what == "save_run") {
        require(wb.saveRun(), "could not save the run (see the log)");
    } else if (what == "compare_run") {
        require(wb.compareRun(int(number(s, "index", 0))), "could not compare the run (see the log)");
    } else if (what == "reopen_run") {
        require(wb.reopenRun(int(number(s, "index", 0))), "could not re-open the run (see the log)");
    } else if (what == "set_light") {
        require(s.contains("position") && s["position"].is_array() && s["position"].size() == 3,
                "needs \"position\": [x, y, z]");
        require(!st.project.scene.lights.empty(), "the scene has no light");
        const json& p = s["position"];
        st.project.scene.setLightPosition(clampToLightRegion(
            st.project.scene, Vec3(p[0].get<float>(), p[1].get<float>(), p[2].get<float>())));
        recordLightOverride(st.project);
        st.markDirty();
        st.request(panels::Command::SceneChanged);
    } else if (what == "select_object") {
        st.view.selectedObject = int(number(s, "id", -1));
    } else if (what == "view") {
        if (s.contains("term")) {
            const std::string t = text(s, "term");
            const std::optional<Term> term = parseTerm(t);
            require(term.has_value(), "unknown term '" + t + "' (global, direct or indirect)");
            st.view.term = *term;
        }
        if (s.contains("metric")) {
            const std::string m = text(s, "metric");
            const std::optional<ErrorMapKind> metric = parseErrorMapKind(m);
            require(metric.has_value(), "unknown metric '" + m + "' (absolute, relative or squared)");
            st.view.metric = *metric;
        }
        st.view.exposure = float(number(s, "exposure", st.view.exposure));
        st.view.errorMax = float(number(s, "error_max", st.view.errorMax));
        st.view.zoom = float(number(s, "zoom", st.view.zoom));
    } else if (what == "open") {
        // Without a path: re-open the current project from disk (checks what a save kept).
        const std::string path = s.contains("path") ? text(s, "path") : st.project.path;
        require(wb.openProject(path), "could not open the project (see the log)");
    } else if (what == "save") {
        require(wb.saveProject(s.contains("path") ? text(s, "path") : std::string()), "could not save (see the log)");
    } else if (what == "export_images") {
        require(wb.exportImages(text(s, "dir")), "could not export images (see the log)");
    } else if (what == "screenshot") {
        st.request(panels::Command::ExportScreenshot, text(s, "path"));
    } else if (what == "frames") {
        if (!waiting_) {
            waiting_ = true;
            framesLeft_ = int(number(s, "count", 1));
        }
        return --framesLeft_ < 0;
    } else if (what == "check") {
        if (s.contains("runs"))
            require(int(st.runs.size()) == int(number(s, "runs", 0)),
                    "expected " + std::to_string(int(number(s, "runs", 0))) + " runs, found " + std::to_string(st.runs.size()));
        if (s.contains("ground_truth_spp_min"))
            require(st.render.spp >= int(number(s, "ground_truth_spp_min", 0)),
                    "ground truth has " + std::to_string(st.render.spp) + " spp");
        if (s.contains("errors"))
            require(int(st.log.errorCount()) == int(number(s, "errors", 0)),
                    "the log has " + std::to_string(st.log.errorCount()) + " errors");
        if (s.contains("dataset"))
            require(!st.dataset.path.empty() == s["dataset"].get<bool>(), "dataset state differs");
        if (s.contains("compare")) require(!st.compare.empty() == s["compare"].get<bool>(), "compare view state differs");
        if (s.contains("prediction"))
            require(!st.prediction.empty() == s["prediction"].get<bool>(), "prediction view state differs");
        if (s.contains("sweeps"))
            require(int(st.cost.sweeps.size()) == int(number(s, "sweeps", 0)), "expected " +
                    std::to_string(int(number(s, "sweeps", 0))) + " sweeps, found " + std::to_string(st.cost.sweeps.size()));
        if (s.contains("evaluated")) require(st.evaluation.valid == s["evaluated"].get<bool>(), "evaluation state differs");
        if (s.contains("train_runs")) {
            int n = 0;
            for (const Run& r : st.runs) n += r.kind == "train" && !r.curves.empty();
            require(n == int(number(s, "train_runs", 0)), "expected " + std::to_string(int(number(s, "train_runs", 0))) +
                                                              " training runs with loss curves, found " + std::to_string(n));
        }
    } else {
        throw std::runtime_error("unknown step '" + what + "'");
    }
    return true;
}

}  // namespace rrf
