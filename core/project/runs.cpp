#include "core/project/runs.h"

#include <algorithm>
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

json objectOr(const JsonReader& r, const char* key) {
    const auto v = r.find(key);
    if (!v) return json::object();
    v->requireObject();
    return v->value();
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

std::optional<double> numberIn(const json& section, const std::string& key) {
    if (!section.is_object()) return std::nullopt;
    const auto it = section.find(key);
    if (it == section.end() || !it->is_number()) return std::nullopt;
    return it->get<double>();
}
}  // namespace

std::optional<double> Run::metric(const std::string& key) const { return numberIn(metrics, key); }
std::optional<double> Run::timing(const std::string& key) const { return numberIn(timings, key); }

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

Run Run::fromJson(const JsonReader& j) {
    j.requireObject();
    Run r;
    r.id = j.stringOr("id", "");
    if (r.id.empty()) j.fail("a run needs a non-empty 'id'");
    r.name = j.stringOr("name", r.id);
    r.kind = j.stringOr("kind", "render");
    r.created = j.stringOr("created", "");
    r.settings = objectOr(j, "settings");
    r.metrics = objectOr(j, "metrics");
    r.timings = objectOr(j, "timings");
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
        if (!known(it.key())) r.extra[it.key()] = it.value();
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
            runs.push_back(Run::fromJson(section.at(i)));
        } catch (const InputError& e) {
            warnings.push_back(std::string(e.what()) + " (run skipped)");
        }
    }
    return runs;
}

json runsToJson(const std::vector<Run>& runs) {
    json list = json::array();
    for (const Run& r : runs) list.push_back(r.toJson());
    return list;
}

std::vector<LossPoint> aggregateLoss(const std::vector<LossCurve>& curves) {
    int last = -1;
    for (const LossCurve& c : curves)
        if (!c.points.empty()) last = std::max(last, c.points.back().epoch);
    std::vector<LossPoint> out;
    if (last < 0) return out;
    std::vector<size_t> at(curves.size(), 0);  // per curve: index of the point for the current epoch
    for (int e = 0; e <= last; ++e) {
        double train = 0, validation = 0, seconds = 0;
        int nTrain = 0, nValidation = 0;
        for (size_t i = 0; i < curves.size(); ++i) {
            const std::vector<LossPoint>& p = curves[i].points;
            if (p.empty() || p.front().epoch > e) continue;
            while (at[i] + 1 < p.size() && p[at[i] + 1].epoch <= e) ++at[i];
            const LossPoint& q = p[at[i]];
            if (std::isfinite(q.train)) train += q.train, ++nTrain;
            if (std::isfinite(q.validation)) validation += q.validation, ++nValidation;
            seconds = std::max(seconds, q.seconds);
        }
        if (nTrain == 0 && nValidation == 0) continue;
        out.push_back({e, nTrain ? train / nTrain : std::numeric_limits<double>::quiet_NaN(), nValidation ? validation / nValidation : std::numeric_limits<double>::quiet_NaN(), seconds});
    }
    return out;
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
