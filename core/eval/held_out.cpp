#include "core/eval/held_out.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/util/rng.h"

namespace rrf {

std::vector<Vec3> heldOutLightPositions(const Bounds3& region, int k, uint64_t seed) {
    std::vector<Vec3> out;
    if (k <= 0) return out;
    // "HELDOUT!" keys a stream of its own: the generator's records use mix64(seed ^ "RECORDS!").
    const uint64_t s = mix64(seed ^ 0x48454C444F555421ULL);
    const Vec3 lo = region.lo, ext = region.empty() ? Vec3(0.f) : region.extent();
    for (int i = 0; i < k; ++i) {
        Rng rng(s, uint64_t(i));
        const float u = rng.uniform(), v = rng.uniform(), w = rng.uniform();
        out.push_back(Vec3(lo.x + ext.x * u, lo.y + ext.y * v, lo.z + ext.z * w));
    }
    return out;
}

void Spread::add(double v) {
    if (count == 0) {
        mean = min = max = v;
    } else {
        mean += (v - mean) / double(count + 1);
        min = std::min(min, v);
        max = std::max(max, v);
    }
    ++count;
}

HeldOutSummary summarizeHeldOut(const std::vector<Evaluation>& evaluations, size_t objectCount) {
    HeldOutSummary s;
    for (int t = 0; t < kTermCount; ++t) s.perObject[t].resize(objectCount);
    for (const Evaluation& e : evaluations)
        for (int t = 0; t < kTermCount; ++t) {
            const TermErrors& te = e.terms[t];
            s.available[t] = s.available[t] && te.available;
            for (size_t id = 0; id < std::min(objectCount, te.perObject.size()); ++id) {
                if (!te.perObject[id].pixels) continue;
                s.perObject[t][id].rmse.add(te.perObject[id].rmse);
                s.perObject[t][id].relativeRmse.add(te.perObject[id].relativeRmse);
            }
            if (te.overall.pixels) {
                s.overall[t].rmse.add(te.overall.rmse);
                s.overall[t].relativeRmse.add(te.overall.relativeRmse);
            }
        }
    return s;
}

nlohmann::json heldOutJson(const Scene& scene, const HeldOutSummary& s) {
    nlohmann::json terms = nlohmann::json::object();
    for (int t = 0; t < kTermCount; ++t) {
        nlohmann::json objects = nlohmann::json::array();
        for (size_t id = 0; id < s.perObject[t].size(); ++id) {
            const HeldOutSummary::Row& r = s.perObject[t][id];
            objects.push_back({{"id", int(id)},
                               {"name", id < scene.objects.size() ? scene.objects[id].name : ""},
                               {"rmse", r.rmse.toJson()},
                               {"relative_rmse", r.relativeRmse.toJson()}});
        }
        terms[termName(Term(t))] = {{"available", s.available[t]},
                                    {"overall", {{"rmse", s.overall[t].rmse.toJson()},
                                                 {"relative_rmse", s.overall[t].relativeRmse.toJson()}}},
                                    {"objects", objects}};
    }
    return terms;
}

std::string heldOutTable(const Scene& scene, const HeldOutSummary& s) {
    std::ostringstream out;
    char line[256];
    std::snprintf(line, sizeof line, "%-9s %-14s %3s | %-29s | %-29s\n", "term", "object", "K", "relative RMSE mean/min/max",
                  "RMSE mean/min/max");
    out << line;
    for (int t = 0; t < kTermCount; ++t) {
        if (!s.available[t]) {
            std::snprintf(line, sizeof line, "%-9s (not predicted by these networks)\n", termName(Term(t)));
            out << line;
            continue;
        }
        auto row = [&](const std::string& name, const HeldOutSummary::Row& r) {
            std::snprintf(line, sizeof line, "%-9s %-14s %3d | %9.4g %9.4g %9.4g | %9.4g %9.4g %9.4g\n", termName(Term(t)),
                          name.substr(0, 14).c_str(), r.rmse.count, r.relativeRmse.mean, r.relativeRmse.min,
                          r.relativeRmse.max, r.rmse.mean, r.rmse.min, r.rmse.max);
            out << line;
        };
        for (size_t id = 0; id < s.perObject[t].size(); ++id)
            if (s.perObject[t][id].rmse.count) row(id < scene.objects.size() ? scene.objects[id].name : std::to_string(id), s.perObject[t][id]);
        row("ALL OBJECTS", s.overall[t]);
    }
    return out.str();
}

}  // namespace rrf
