// The project's "runs" section in JSON (see runs_json.h).
#include "core/project/runs_json.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/data/sampling_settings_json.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/trainer_config_json.h"
#include "core/project/scene_overrides_json.h"
#include "core/render/render_settings_json.h"

namespace rrf {

using nlohmann::json;

namespace {
const char* const kKnownKeys[] = {"id", "name", "kind", "created", "settings", "loss", "metrics", "timings",
                                  "artifacts", "curves"};

bool known(const std::string& key) {
    for (const char* k : kKnownKeys)
        if (key == k) return true;
    return false;
}

// JSON has no NaN: a missing validation loss is written as null and read back as NaN.
json numberOrNull(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double numberFrom(const json& v) {
    return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

json lossJson(const std::vector<LossPoint>& loss) {
    json l = json::array();
    for (const LossPoint& p : loss)
        l.push_back(json::array({p.epoch, numberOrNull(p.train), numberOrNull(p.validation), p.seconds}));
    return l;
}

std::vector<LossPoint> lossFromJson(const JsonReader& r) {
    std::vector<LossPoint> loss;
    const size_t n = r.requireArray();
    for (size_t i = 0; i < n; ++i) {
        const JsonReader p = r.at(i);
        if (!p.isArray() || p.value().size() != 4)
            p.fail("expected [epoch, train, validation, seconds], got " + JsonReader::describe(p.value()));
        loss.push_back({int(p.at(size_t(0)).integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max())), numberFrom(p.value()[1]),
                        numberFrom(p.value()[2]), numberFrom(p.value()[3])});
    }
    return loss;
}

// Typed fields <-> JSON. Each struct lists its fields once, in visit*; reading and writing both walk
// that list, so a key cannot be read under one name and written under another.

template <class M, class F>
void visitMetrics(M& m, F&& f) {
    f("spp", m.spp);
    f("relative_error", m.relativeError);
    f("non_finite_samples", m.nonFiniteSamples);
    f("samples_per_second", m.samplesPerSecond);
    f("networks", m.networks);
    f("skipped", m.skipped);
    f("epochs", m.epochs);
    f("planned_networks", m.plannedNetworks);
    f("stopped", m.stopped);
    f("leaves", m.leaves);
    f("records", m.records);
    f("relative_rmse", m.relativeRmse);
    f("rmse", m.rmse);
    f("mae", m.mae);
    f("evaluated_spp", m.evaluatedSpp);
    f("evaluated_width", m.evaluatedWidth);
    f("evaluated_height", m.evaluatedHeight);
    f("relative_rmse_noise_floor", m.relativeRmseNoiseFloor);
    f("relative_rmse_corrected", m.relativeRmseCorrected);
    f("evaluated_light", m.evaluatedLight);
    f("evaluated_lights", m.evaluatedLights);
    f("frame_seconds", m.frameSeconds);
    f("frame_width", m.frameWidth);
    f("frame_height", m.frameHeight);
    f("glsl_frame_seconds", m.glslFrameSeconds);
    f("glsl_frame_width", m.glslFrameWidth);
    f("glsl_frame_height", m.glslFrameHeight);
}

template <class T, class F>
void visitTimings(T& t, F&& f) {
    f("render", t.render);
    f("train", t.train);
    f("generate", t.generate);
    f("evaluate", t.evaluate);
}

// A recorded double may be non-finite (an estimate without enough samples): JSON has no NaN, so it is
// written as null (nlohmann's own spelling of it) and null reads back as NaN.
void readValue(const JsonReader& r, std::optional<double>& v) {
    v = r.value().is_null() ? std::numeric_limits<double>::quiet_NaN() : r.number();
}
void readValue(const JsonReader& r, std::optional<int>& v) {
    v = int(r.integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}
void readValue(const JsonReader& r, std::optional<int64_t>& v) {
    v = r.integer(std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max());
}
void readValue(const JsonReader& r, std::optional<uint64_t>& v) { v = r.unsignedInteger(); }
void readValue(const JsonReader& r, std::optional<bool>& v) { v = r.boolean(); }
void readValue(const JsonReader& r, std::optional<Vec3>& v) { v = r.vec3(); }

json toJsonValue(double v) { return numberOrNull(v); }
json toJsonValue(const Vec3& v) { return json::array({v.x, v.y, v.z}); }
template <class T>
json toJsonValue(const T& v) {
    return json(v);
}

/// Reads the members of `section` that `visit` lists; every other member goes to `other` verbatim.
template <class S, class Visit>
S readFields(const JsonReader& section, Visit visit) {
    section.requireObject();
    S s;
    json other = json::object();
    std::vector<std::string> knownKeys;
    visit(s, [&](const char* key, auto& field) {
        knownKeys.push_back(key);
        if (const auto v = section.find(key)) readValue(*v, field);
    });
    for (auto it = section.value().begin(); it != section.value().end(); ++it)
        if (std::find(knownKeys.begin(), knownKeys.end(), it.key()) == knownKeys.end()) other[it.key()] = it.value();
    s.other = jsonText(other);
    return s;
}

template <class S, class Visit>
json writeFields(const S& s, Visit visit) {
    json j = parseJsonText(s.other);
    visit(s, [&](const char* key, const auto& field) {
        if (field) j[key] = toJsonValue(*field);
    });
    return j;
}

const char* const kSettingsKeys[] = {"render",  "light_position", "scene_hash", "scene_overrides", "network",
                                     "trainer", "dataset",        "sampling",   "kernel"};

/// Reads the settings section `key` with `read` into `field`. A section this build cannot read (one a
/// newer build wrote: a trainer type, an encoding or a key it does not know) must not cost the user
/// the run: its JSON is kept in `other` (the settings' unknown keys) and written back as it was, with a warning, and the run
/// shows without those settings (re-opening it cannot restore them).
template <class T, class Read>
void readSection(const JsonReader& j, const char* key, std::optional<T>& field, json& other,
                 std::vector<std::string>& warnings, Read read) {
    const auto v = j.find(key);
    if (!v) return;
    try {
        field = read(*v);
    } catch (const InputError& e) {
        warnings.push_back(std::string(e.what()) + " (kept as written; this run's " + key + " settings are not used)");
        other[key] = v->value();
    }
}

RunSettings settingsFromJson(const JsonReader& j, std::vector<std::string>& warnings) {
    j.requireObject();
    RunSettings s;
    json other = json::object();
    readSection(j, "render", s.render, other, warnings, [](const JsonReader& v) { return parseRenderSettings(v); });
    if (const auto v = j.find("light_position")) s.lightPosition = v->vec3();
    if (const auto v = j.find("scene_hash")) s.sceneHash = v->string();
    readSection(j, "scene_overrides", s.sceneOverrides, other, warnings,
                [&](const JsonReader& v) { return sceneOverridesFromJson(v, warnings); });
    readSection(j, "trainer", s.trainer, other, warnings, [](const JsonReader& v) { return trainerConfigFromJson(v); });
    readSection(j, "network", s.network, other, warnings, [](const JsonReader& v) { return networkSettingsFromJson(v); });
    if (const auto v = j.find("dataset")) s.dataset = v->string();
    readSection(j, "sampling", s.sampling, other, warnings, [](const JsonReader& v) { return samplingSettingsFromJson(v); });
    if (const auto v = j.find("kernel")) s.kernel = v->string();
    for (auto it = j.value().begin(); it != j.value().end(); ++it)
        if (std::find_if(std::begin(kSettingsKeys), std::end(kSettingsKeys),
                         [&](const char* k) { return it.key() == k; }) == std::end(kSettingsKeys))
            other[it.key()] = it.value();
    s.other = jsonText(other);
    return s;
}

json settingsToJson(const RunSettings& s) {
    json j = parseJsonText(s.other);
    if (s.render) j["render"] = renderSettingsToJson(*s.render);
    if (s.lightPosition) j["light_position"] = toJsonValue(*s.lightPosition);
    if (s.sceneHash) j["scene_hash"] = *s.sceneHash;
    if (s.sceneOverrides) j["scene_overrides"] = toJson(*s.sceneOverrides);
    if (s.network) j["network"] = toJson(*s.network);
    if (s.trainer) j["trainer"] = toJson(*s.trainer);
    if (s.dataset) j["dataset"] = *s.dataset;
    if (s.sampling) j["sampling"] = toJson(*s.sampling);
    if (s.kernel) j["kernel"] = *s.kernel;
    return j;
}

const auto kMetrics = [](auto& m, auto&& f) { visitMetrics(m, f); };
const auto kTimings = [](auto& t, auto&& f) { visitTimings(t, f); };
}  // namespace

json toJson(const Run& run) {
    json j = parseJsonText(run.extra);
    j["id"] = run.id;
    j["name"] = run.name;
    j["kind"] = run.kind;
    j["created"] = run.created;
    j["settings"] = settingsToJson(run.settings);
    j["loss"] = lossJson(run.loss);
    if (!run.curves.empty()) {
        json c = json::array();
        for (const LossCurve& curve : run.curves)
            c.push_back(json{{"object", curve.objectId}, {"name", curve.object}, {"target", curve.target},
                             {"loss", lossJson(curve.points)}});
        j["curves"] = c;
    }
    j["metrics"] = writeFields(run.metrics, kMetrics);
    j["timings"] = writeFields(run.timings, kTimings);
    j["artifacts"] = run.artifacts;
    return j;
}

Run runFromJson(const JsonReader& j, std::vector<std::string>& warnings) {
    j.requireObject();
    Run r;
    json extra = json::object();
    r.id = j.stringOr("id", "");
    if (r.id.empty()) j.fail("a run needs a non-empty 'id'");
    r.name = j.stringOr("name", r.id);
    r.kind = j.stringOr("kind", "render");
    r.created = j.stringOr("created", "");
    if (const auto v = j.find("settings")) r.settings = settingsFromJson(*v, warnings);
    if (const auto v = j.find("metrics")) r.metrics = readFields<RunMetrics>(*v, kMetrics);
    if (const auto v = j.find("timings")) r.timings = readFields<RunTimings>(*v, kTimings);
    if (const auto loss = j.find("loss")) r.loss = lossFromJson(*loss);
    if (const auto curves = j.find("curves")) {
        const size_t n = curves->requireArray();
        for (size_t i = 0; i < n; ++i) {
            const JsonReader c = curves->at(i);
            LossCurve curve;
            curve.objectId = int(c.at("object").integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
            curve.object = c.stringOr("name", std::to_string(curve.objectId));
            curve.target = c.stringOr("target", "global");
            if (const auto loss = c.find("loss")) curve.points = lossFromJson(*loss);
            r.curves.push_back(std::move(curve));
        }
    }
    if (const auto artifacts = j.find("artifacts")) {
        const size_t n = artifacts->requireArray();
        for (size_t i = 0; i < n; ++i) r.artifacts.push_back(artifacts->at(i).string());
    }
    for (auto it = j.value().begin(); it != j.value().end(); ++it)
        if (!known(it.key())) extra[it.key()] = it.value();
    r.extra = jsonText(extra);
    return r;
}

std::vector<Run> readRuns(const JsonReader& section, std::vector<std::string>& warnings) {
    std::vector<Run> runs;
    if (!section.isArray()) {
        warnings.push_back(InputError(section.file(), section.pointer(),
                                      "expected an array, got " + JsonReader::describe(section.value()) +
                                          "; the runs were not loaded")
                               .what());
        return runs;
    }
    for (size_t i = 0; i < section.value().size(); ++i) {
        try {
            std::vector<std::string> overrideWarnings;
            runs.push_back(runFromJson(section.at(i), overrideWarnings));
            warnings.insert(warnings.end(), overrideWarnings.begin(), overrideWarnings.end());
        } catch (const InputError& e) {
            warnings.push_back(std::string(e.what()) + " (run skipped)");
        }
    }
    return runs;
}

json runsToJson(const std::vector<Run>& runs) {
    json list = json::array();
    for (const Run& r : runs) list.push_back(toJson(r));
    return list;
}

}  // namespace rrf
