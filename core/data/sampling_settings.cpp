#include "core/data/sampling_settings.h"

#include "core/util/error.h"

namespace rrf {

namespace {
int readInt(const nlohmann::json& j, const char* key, int lo, int hi, const std::string& file, const std::string& path,
            int fallback) {
    if (!j.contains(key)) return fallback;
    const nlohmann::json& v = j.at(key);
    if (!v.is_number_integer()) throw InputError(file, path + "/" + key, "expected an integer, got " + std::string(v.type_name()));
    const long long x = v.get<long long>();
    if (x < lo || x > hi)
        throw InputError(file, path + "/" + key, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(x));
    return int(x);
}
}  // namespace

SamplingSettings SamplingSettings::fromJson(const nlohmann::json& j, const std::string& file, const std::string& path) {
    SamplingSettings s;
    if (!j.is_object()) throw InputError(file, path, "expected an object, got " + std::string(j.type_name()));
    for (auto it = j.begin(); it != j.end(); ++it) {
        static const char* known[] = {"grid", "directions", "spp", "seed", "light", "estimator", "max_depth"};
        if (std::find(std::begin(known), std::end(known), it.key()) == std::end(known))
            throw InputError(file, path + "/" + it.key(), "unknown key (known: grid, directions, spp, seed, light, estimator, max_depth)");
    }
    if (j.contains("grid")) {
        const nlohmann::json& g = j.at("grid");
        if (!g.is_array() || g.size() != 3 || !g[0].is_number_integer() || !g[1].is_number_integer() || !g[2].is_number_integer())
            throw InputError(file, path + "/grid", "expected an array of 3 integers [nx, ny, nz]");
        int* dims[] = {&s.nx, &s.ny, &s.nz};
        for (int i = 0; i < 3; ++i) {
            const long long v = g[size_t(i)].get<long long>();
            if (v < 1 || v > 1000) throw InputError(file, path + "/grid/" + std::to_string(i), "expected 1..1000 cells, got " + std::to_string(v));
            *dims[i] = int(v);
        }
    }
    s.directions = readInt(j, "directions", 1, 10000000, file, path, s.directions);
    s.spp = readInt(j, "spp", 1, 1000000, file, path, s.spp);
    s.maxDepth = readInt(j, "max_depth", 1, 1000, file, path, s.maxDepth);
    if (j.contains("seed")) {
        if (!j.at("seed").is_number_unsigned()) throw InputError(file, path + "/seed", "expected a non-negative integer");
        s.seed = j.at("seed").get<uint64_t>();
    }
    if (j.contains("light")) {
        const nlohmann::json& l = j.at("light");
        if (!l.is_string() || (l != "region" && l != "fixed"))
            throw InputError(file, path + "/light", "expected \"region\" (sample the light region) or \"fixed\"");
        s.fixedLight = l == "fixed";
    }
    if (j.contains("estimator")) {
        const nlohmann::json& e = j.at("estimator");
        if (!e.is_string() || (e != "nee" && e != "naive")) throw InputError(file, path + "/estimator", "expected \"nee\" or \"naive\"");
        s.estimator = e == "nee" ? Estimator::NEE : Estimator::Naive;
    }
    return s;
}

nlohmann::json SamplingSettings::toJson() const {
    return {{"grid", {nx, ny, nz}},
            {"directions", directions},
            {"spp", spp},
            {"seed", seed},
            {"light", fixedLight ? "fixed" : "region"},
            {"estimator", estimator == Estimator::NEE ? "nee" : "naive"},
            {"max_depth", maxDepth}};
}

}  // namespace rrf
