#include "core/project/runs.h"

#include <cmath>
#include <ctime>
#include <limits>
#include <stdexcept>

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

std::string stringOr(const json& j, const char* key, const std::string& fallback) {
    if (!j.contains(key)) return fallback;
    if (!j[key].is_string()) throw std::invalid_argument(std::string("'") + key + "' must be a string");
    return j[key].get<std::string>();
}

json objectOr(const json& j, const char* key) {
    if (!j.contains(key)) return json::object();
    if (!j[key].is_object()) throw std::invalid_argument(std::string("'") + key + "' must be an object");
    return j[key];
}

// JSON has no NaN: a missing validation loss is written as null and read back as NaN.
json numberOrNull(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double numberFrom(const json& v) {
    return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

std::string formatTime(const char* fmt) {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    localtime_r(&now, &tm);
    char buf[64];
    std::strftime(buf, sizeof buf, fmt, &tm);
    return buf;
}

json lossJson(const std::vector<LossPoint>& loss) {
    json l = json::array();
    for (const LossPoint& p : loss)
        l.push_back(json::array({p.epoch, numberOrNull(p.train), numberOrNull(p.validation), p.seconds}));
    return l;
}

std::vector<LossPoint> lossFromJson(const json& j) {
    if (!j.is_array()) throw std::invalid_argument("'loss' must be an array");
    std::vector<LossPoint> loss;
    for (const json& p : j) {
        if (!p.is_array() || p.size() != 4 || !p[0].is_number_integer())
            throw std::invalid_argument("'loss' entries must be [epoch, train, validation, seconds]");
        loss.push_back({p[0].get<int>(), numberFrom(p[1]), numberFrom(p[2]), numberFrom(p[3])});
    }
    return loss;
}
}  // namespace

json Run::toJson() const {
    json j = extra.is_object() ? extra : json::object();
    j["id"] = id;
    j["name"] = name;
    j["kind"] = kind;
    j["created"] = created;
    j["settings"] = settings;
    j["loss"] = lossJson(loss);
    if (!curves.empty()) {
        json c = json::array();
        for (const LossCurve& curve : curves)
            c.push_back(json{{"object", curve.objectId}, {"name", curve.object}, {"target", curve.target},
                             {"loss", lossJson(curve.points)}});
        j["curves"] = c;
    }
    j["metrics"] = metrics;
    j["timings"] = timings;
    j["artifacts"] = artifacts;
    return j;
}

Run Run::fromJson(const json& j) {
    if (!j.is_object()) throw std::invalid_argument("a run must be an object");
    Run r;
    r.id = stringOr(j, "id", "");
    if (r.id.empty()) throw std::invalid_argument("a run needs a non-empty 'id'");
    r.name = stringOr(j, "name", r.id);
    r.kind = stringOr(j, "kind", "render");
    r.created = stringOr(j, "created", "");
    r.settings = objectOr(j, "settings");
    r.metrics = objectOr(j, "metrics");
    r.timings = objectOr(j, "timings");
    if (j.contains("loss")) r.loss = lossFromJson(j["loss"]);
    if (j.contains("curves")) {
        if (!j["curves"].is_array()) throw std::invalid_argument("'curves' must be an array");
        for (const json& c : j["curves"]) {
            if (!c.is_object() || !c.contains("object") || !c["object"].is_number_integer())
                throw std::invalid_argument("'curves' entries need an integer 'object'");
            LossCurve curve;
            curve.objectId = c["object"].get<int>();
            curve.object = stringOr(c, "name", std::to_string(curve.objectId));
            curve.target = stringOr(c, "target", "global");
            if (c.contains("loss")) curve.points = lossFromJson(c["loss"]);
            r.curves.push_back(std::move(curve));
        }
    }
    if (j.contains("artifacts")) {
        if (!j["artifacts"].is_array()) throw std::invalid_argument("'artifacts' must be an array");
        for (const json& a : j["artifacts"]) {
            if (!a.is_string()) throw std::invalid_argument("'artifacts' entries must be strings");
            r.artifacts.push_back(a.get<std::string>());
        }
    }
    for (auto it = j.begin(); it != j.end(); ++it)
        if (!known(it.key())) r.extra[it.key()] = it.value();
    return r;
}

std::vector<Run> runsFromDoc(const json& doc, std::vector<std::string>* problems) {
    std::vector<Run> runs;
    if (!doc.is_object() || !doc.contains("runs")) return runs;
    const json& list = doc["runs"];
    if (!list.is_array()) {
        if (problems) problems->push_back("/runs: expected an array; the runs were not loaded");
        return runs;
    }
    for (size_t i = 0; i < list.size(); ++i) {
        try {
            runs.push_back(Run::fromJson(list[i]));
        } catch (const std::exception& e) {
            if (problems) problems->push_back("/runs/" + std::to_string(i) + ": " + e.what() + " (run skipped)");
        }
    }
    return runs;
}

void storeRunsInDoc(const std::vector<Run>& runs, json& doc) {
    if (!doc.is_object()) doc = json::object();
    if (runs.empty()) {
        doc.erase("runs");
        return;
    }
    json list = json::array();
    for (const Run& r : runs) list.push_back(r.toJson());
    doc["runs"] = std::move(list);
}

std::string newRunId(const std::vector<Run>& runs, const std::string& kind) {
    const std::string base = kind + "-" + formatTime("%Y%m%d-%H%M%S");
    auto used = [&](const std::string& id) {
        for (const Run& r : runs)
            if (r.id == id) return true;
        return false;
    };
    std::string id = base;
    for (int n = 2; used(id); ++n) id = base + "-" + std::to_string(n);
    return id;
}

std::string localTimestamp() { return formatTime("%Y-%m-%dT%H:%M:%S"); }

}  // namespace rrf
