// The reference store's files (see reference_store_file.h).
#include "core/eval/reference_store_file.h"

#include <filesystem>

#include "core/eval/error_metrics_json.h"
#include "core/eval/reference_file.h"
#include "core/eval/reference_noise_json.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "core/util/text_format.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
constexpr const char* kEntryFormat = "rrf reference 1";
}  // namespace

json toJson(const ReferenceKey& k) {
    return {{"scene_hash", hexString16(k.sceneHash)}, {"camera_hash", hexString16(k.cameraHash)},
            {"light_position", {k.lightPosition.x, k.lightPosition.y, k.lightPosition.z}},
            {"width", k.width}, {"height", k.height}, {"estimator", estimatorName(k.estimator)},
            {"max_depth", k.maxDepth}, {"seed", k.seed}};
}

ReferenceKey referenceKeyFromJson(const json& j, const std::string& file, const std::string& pointer) {
    const JsonReader r(j, file, pointer);
    r.checkKeys({"scene_hash", "camera_hash", "light_position", "width", "height", "estimator", "max_depth", "seed"});
    auto hash = [&](const char* name) {
        const JsonReader f = r.at(name);
        const std::string s = f.string();
        if (s.size() != 16 || s.find_first_not_of("0123456789abcdef") != std::string::npos)
            f.fail("expected 16 hex digits, got \"" + s + "\"");
        return uint64_t(std::stoull(s, nullptr, 16));
    };
    ReferenceKey k;
    k.sceneHash = hash("scene_hash");
    k.cameraHash = hash("camera_hash");
    k.lightPosition = r.at("light_position").vec3();
    k.width = int(r.at("width").integer(1, kMaxImageSide));
    k.height = int(r.at("height").integer(1, kMaxImageSide));
    const std::string e = r.choiceOr("estimator", "", {"nee", "naive", "bdpt"});
    if (e.empty()) r.fail("missing required field 'estimator'");
    k.estimator = *parseEstimator(e);
    k.maxDepth = int(r.at("max_depth").integer(1, 1 << 16));
    k.seed = r.at("seed").unsignedInteger();
    return k;
}

StoredReference readReferenceEntry(const std::string& directory) {
    const fs::path dir(directory);
    const std::string meta = (dir / kReferenceEntryFile).string();
    const json j = readJsonFile(meta);
    StoredReference r;
    try {
        if (j.at("format").get<std::string>() != kEntryFormat)
            throw InputError(meta, "/format", std::string("expected \"") + kEntryFormat + "\"");
        r.key = referenceKeyFromJson(j.at("key"), meta, "/key");
        r.spp = j.at("spp").get<int>();
        r.seconds = j.at("seconds").get<double>();
        r.noise = referenceNoiseFromJson(j.at("noise"));
        r.complete = j.at("complete").get<bool>();
        r.wantedNoise = noiseFigureFromJson(j.at("wanted_noise"));
    } catch (const json::exception& e) {
        throw InputError(meta, "", std::string("not a reference entry written by the reference store: ") + e.what());
    }
    r.dir = dir.string();
    if (dir.filename().string() != r.key.id())
        throw InputError(meta, "/key", "the key's id is " + r.key.id() + ", the directory is " + dir.filename().string());
    return r;
}

void writeReferenceEntryFiles(const std::string& dir, const ReferenceKey& key, const Reference& ref,
                              const ReferenceNoise& noise, const ReferenceEntryFigures& figures,
                              const std::string& stateFile, const std::string& stateChecksum) {
    writeReferenceDescription(dir, ref, key.width, key.height, "reference store");
    const json meta{{"format", kEntryFormat},
                    {"key", toJson(key)},
                    {"spp", figures.spp},
                    {"seconds", figures.seconds},
                    {"noise", toJson(noise)},
                    {"noise_metric", "relative RMSE noise floor over the footprint mask (docs/design.md §14)"},
                    {"complete", figures.complete},
                    {"wanted_noise", noiseFigureJson(figures.wantedNoise)},
                    {"non_finite_samples_dropped", figures.nonFinite},
                    {"state", {{"file", stateFile}, {"checksum64", stateChecksum}}}};
    writeFileAtomically((fs::path(dir) / kReferenceEntryFile).string(), meta.dump(2) + "\n");
}

}  // namespace rrf
