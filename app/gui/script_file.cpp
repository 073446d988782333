#include "app/gui/script_file.h"

#include <limits>

#include <nlohmann/json.hpp>

#include "core/data/sampling_settings_json.h"
#include "core/eval/error_metrics.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/trainers/registry.h"
#include "core/util/json_reader.h"
#include "panels/workbench_state.h"

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
                       "full_frame_banded", "uploads_announced", "longest_frame_ms_max"}},
        };
    }();
    return keys;
}

/// check's counts (compared exactly, or as a minimum) and flags.
constexpr const char* kCheckCounts[] = {"runs",       "ground_truth_spp_min", "errors",      "undo_steps",
                                        "redo_steps", "status_idle_while_pipeline", "sweeps", "objects_rows",
                                        "region_pixels_min", "light_grid_points", "train_runs", "stopped_runs",
                                        "panes",      "clipped",              "longest_frame_ms_max"};
constexpr const char* kCheckFlags[] = {"dataset",         "compare",          "prediction",       "help_open",
                                       "ground_truth_stored", "error_waiting", "evaluated",        "full_frame_banded",
                                       "uploads_announced", "programs_cached", "flip_evaluated",   "spread_shown",
                                       "spread_evaluated", "unsaved_prompt",   "dirty",            "prediction_partial",
                                       "render_cancelled", "notice",           "pipeline_done",    "pipeline_stopped",
                                       "pair"};

/// The step without "do" and `also`: the settings section it carries, at the step's own JSON pointer.
ScriptSection sectionOf(const JsonReader& step, std::initializer_list<const char*> also) {
    json section = step.value();
    section.erase("do");
    for (const char* key : also) section.erase(key);
    return {jsonText(section), step.file(), step.pointer()};
}

int intOr(const JsonReader& s, const char* key, int fallback) {
    return int(s.integerOr(key, fallback, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

std::optional<int> optionalInt(const JsonReader& s, const char* key, int lo, int hi) {
    if (!s.has(key)) return std::nullopt;
    return int(s.at(key).integer(lo, hi));
}

std::optional<float> optionalFloat(const JsonReader& s, const char* key) {
    if (!s.has(key)) return std::nullopt;
    return s.floatOr(key, 0.f);
}

ScriptStep readStep(const JsonReader& r) {
    ScriptStep s;
    s.what = r.at("do").string();
    s.file = r.file();
    s.pointer = r.pointer();
    const std::string& what = s.what;
    if (what == "render") {
        s.spp = optionalInt(r, "spp", 1, 1 << 30);
        // The image size as the project's "render" section takes it (0: the scene camera's).
        s.width = optionalInt(r, "width", 0, kMaxImageSide);
        s.height = optionalInt(r, "height", 0, kMaxImageSide);
    } else if (what == "wait") {
        s.waitFor = r.choiceOr("for", "jobs", {"render", "jobs", "train_epoch", "pipeline", "train_running", "flip",
                                               "spread", "full_frame", "loads"});
        s.timeoutSeconds = r.numberOr("timeout_s", 300, 0, 1e9);
    } else if (what == "generate") {
        s.sampling = sectionOf(r, {});
    } else if (what == "train") {
        s.network = sectionOf(r, {"epochs", "trainer", "refused"});
        if (r.has("trainer")) s.trainer = r.choiceOr("trainer", "", trainerTypeNames());
        s.refused = r.booleanOr("refused", false);
        s.epochs = intOr(r, "epochs", 0);
    } else if (what == "sweep") {
        s.sweepWhat = r.at("what").string();
    } else if (what == "light_grid") {
        if (r.has("grid")) {
            const JsonReader g = r.at("grid");
            std::array<int, 3> counts{};
            for (int a = 0; a < 3; ++a) counts[size_t(a)] = int(g.at(size_t(a)).integer(1, panels::LightRegionInfo::kMaxCount));
            s.grid = counts;
        }
    } else if (what == "pipeline") {
        s.preset = r.has("preset") ? r.choiceOr("preset", "", {"quick", "paper", "default", "best"}) : "";
        s.sampling = sectionOf(r, {"preset", "epochs", "hidden"});
        if (r.has("hidden")) s.network = {jsonText(json{{"hidden", r.at("hidden").value()}}), r.file(), r.pointer()};
        if (r.has("epochs")) s.pipelineEpochs = intOr(r, "epochs", 1);
    } else if (what == "measure_frames") {
        s.frames = intOr(r, "frames", 60);
        s.dragLight = r.booleanOr("drag_light", false);
        s.label = r.stringOr("label", "");
    } else if (what == "tab") {
        s.tabName = r.at("name").string();
    } else if (what == "move_tab") {
        s.moveTab = r.at("tab").string();
        s.moveTo = r.at("to").string();
        s.side = r.choiceOr("side", "centre", {"centre", "left", "right", "top", "bottom"});
    } else if (what == "compare_run" || what == "reopen_run") {
        s.index = intOr(r, "index", 0);
    } else if (what == "set_light") {
        s.position = r.at("position").vec3();
    } else if (what == "select_object") {
        s.objectId = intOr(r, "id", -1);
    } else if (what == "view") {
        if (r.has("term")) s.term = r.choiceOr("term", "", {"global", "direct", "indirect"});
        if (r.has("metric")) {
            // Every error map kind, and "flip" for the Views' FLIP map.
            static_assert(std::size(kErrorMapKinds) == 6, "every error map kind is a script choice");
            s.metric = r.choiceOr("metric", "", {errorMapName(kErrorMapKinds[0]), errorMapName(kErrorMapKinds[1]),
                                                 errorMapName(kErrorMapKinds[2]), errorMapName(kErrorMapKinds[3]),
                                                 errorMapName(kErrorMapKinds[4]), errorMapName(kErrorMapKinds[5]), "flip"});
        }
        s.exposure = optionalFloat(r, "exposure");
        s.errorMax = optionalFloat(r, "error_max");
        s.zoom = optionalFloat(r, "zoom");
        if (r.has("spread")) s.spread = r.booleanOr("spread", false);
        // region: [x0, y0, x1, y1] (x1, y1 exclusive), as a right-drag draws it; [] clears it.
        if (const auto g = r.find("region")) {
            const size_t n = g->requireArray();
            if (n != 0 && n != 4) g->fail("expected [x0, y0, x1, y1] or []");
            std::vector<int> region;
            for (size_t i = 0; i < n; ++i) region.push_back(int(g->at(i).integer(0, 1 << 20)));
            s.region = region;
        }
    } else if (what == "open" || what == "request_open") {
        if (r.has("path")) s.path = r.stringOr("path", "");
    } else if (what == "save") {
        s.path = r.stringOr("path", "");
    } else if (what == "answer_unsaved") {
        s.choice = r.choiceOr("choice", "", {"save", "discard", "cancel"});
    } else if (what == "compare_runs") {
        s.runA = intOr(r, "a", 0);
        s.runB = intOr(r, "b", 1);
    } else if (what == "stop") {
        s.job = r.choiceOr("job", "", {"render", "generate", "train"});
    } else if (what == "export_images") {
        s.dir = r.at("dir").string();
    } else if (what == "screenshot") {
        s.path = r.at("path").string();
    } else if (what == "shortcut") {
        s.keys = r.at("keys").string();
    } else if (what == "frames") {
        s.frameCount = intOr(r, "count", 1);
    } else if (what == "check") {
        for (const char* key : kCheckCounts)
            if (const auto v = r.find(key)) s.counts[key] = v->integer(0, std::numeric_limits<int>::max());
        for (const char* key : kCheckFlags)
            if (const auto v = r.find(key)) s.flags[key] = v->boolean();
        if (const auto v = r.find("prediction_label")) s.predictionLabel = v->string();
        if (const auto v = r.find("light_position")) s.lightPosition = v->vec3();
        if (const auto v = r.find("same_pane")) {
            const JsonReader pair = *v;
            if (pair.requireArray() != 2) pair.fail("expected an array of 2 tab names");
            s.samePane = std::make_pair(pair.at(size_t(0)).string(), pair.at(size_t(1)).string());
        }
    }
    return s;
}
}  // namespace

void ScriptStep::fail(const std::string& key, const std::string& what) const {
    throw InputError(file, JsonReader::child(pointer, key), what);
}

SamplingSettings samplingOver(const ScriptSection& section, const SamplingSettings& base) {
    const json keys = parseJsonText(section.keys);
    return samplingSettingsFromJson(JsonReader(keys, section.file, section.pointer), base);
}

NetworkSettings networkOver(const ScriptSection& section, const NetworkSettings& base) {
    const json keys = parseJsonText(section.keys);
    return networkSettingsFromJson(JsonReader(keys, section.file, section.pointer), base);
}

std::vector<ScriptStep> readScriptFile(const std::string& path) {
    const json steps = readJsonFile(path);
    const JsonReader root(steps, path);
    if (!root.isArray()) root.fail("a script is a JSON array of steps, got " + JsonReader::describe(steps));
    std::vector<ScriptStep> out;
    for (size_t i = 0; i < steps.size(); ++i) {
        const JsonReader step = root.at(i);
        const std::string what = step.at("do").string();
        const auto keys = stepKeys().find(what);
        if (keys == stepKeys().end()) step.at("do").fail("unknown step '" + what + "'");
        std::vector<std::string> allowed = {"do"};
        allowed.insert(allowed.end(), keys->second.begin(), keys->second.end());
        step.checkKeys(allowed);
        out.push_back(readStep(step));
    }
    return out;
}

}  // namespace rrf
