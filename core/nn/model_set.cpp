#include "core/nn/model_set.h"

#include <filesystem>

#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/render/render_outputs.h"
#include "core/util/text_format.h"

namespace rrf {

namespace fs = std::filesystem;

const ObjectNetworks* ModelSet::find(int objectId) const {
    for (const ObjectNetworks& o : objects)
        if (o.objectId == objectId) return &o;
    return nullptr;
}

nlohmann::json saveModelSet(const std::string& dir, const std::vector<ObjectModel>& trained, uint64_t sceneHash,
                            const std::vector<std::string>& inputLayout, const nlohmann::json& extra) {
    makeDirectories(dir);
    nlohmann::json index = extra.is_object() ? extra : nlohmann::json::object();
    index["format"] = "rrf-models";
    index["version"] = 1;
    index["scene_hash"] = hexString(sceneHash);
    index["input_layout"] = inputLayout;
    nlohmann::json models = nlohmann::json::array();
    for (const ObjectModel& m : trained) {
        if (m.skipped) {
            models.push_back({{"object", m.objectId}, {"name", m.objectName}, {"target", m.target}, {"skipped", m.message}});
            continue;
        }
        const std::string file = modelFileName(m.objectId, m.target);
        saveModel(m.model, (fs::path(dir) / file).string());
        models.push_back({{"object", m.objectId},
                          {"name", m.objectName},
                          {"target", m.target},
                          {"file", file},
                          {"architecture", m.model.arch.describe()},
                          {"parameters", m.model.arch.numParams()},
                          {"epochs", m.model.training.epochs},
                          {"seconds", m.model.training.seconds},
                          {"rmse", {{"train", m.model.errors.train}, {"validation", m.model.errors.validation}, {"test", m.model.errors.test}}}});
    }
    index["models"] = models;
    // NaN errors (empty validation sets) are not valid JSON numbers: nlohmann writes null for them.
    writeFileAtomically((fs::path(dir) / "models.json").string(), index.dump(2) + "\n");
    return index;
}

ModelSet loadModelSet(const std::string& dir, uint64_t expectedSceneHash) {
    ModelSet set;
    set.dir = dir;
    const std::string indexPath = (fs::path(dir) / "models.json").string();
    std::string text;
    try {
        text = readFile(indexPath);
    } catch (const std::exception&) {
        throw InputError(indexPath, "", "no model index here: train models first (rrf train ... --out " + dir + ")");
    }
    try {
        set.index = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(indexPath, "", std::string("malformed JSON: ") + e.what());
    }
    try {
        set.sceneHash = std::stoull(set.index.at("scene_hash").get<std::string>(), nullptr, 16);
        set.inputLayout = set.index.at("input_layout").get<std::vector<std::string>>();
        if (expectedSceneHash != 0 && set.sceneHash != expectedSceneHash)
            throw InputError(indexPath, "/scene_hash", "these models were trained for a different scene: retrain them for this project");
        const nlohmann::json& models = set.index.at("models");
        for (size_t i = 0; i < models.size(); ++i) {
            const nlohmann::json& m = models[i];
            if (!m.contains("file")) continue;  // skipped object
            const std::string file = (fs::path(dir) / m.at("file").get<std::string>()).string();
            NetworkModel model = loadModel(file);
            if (model.arch.inputs != int(set.inputLayout.size()))
                throw InputError(file, "", "network has " + std::to_string(model.arch.inputs) + " inputs but the index lists " +
                                               std::to_string(set.inputLayout.size()));
            const int id = m.at("object").get<int>();
            ObjectNetworks* o = nullptr;
            for (ObjectNetworks& x : set.objects)
                if (x.objectId == id) o = &x;
            if (!o) {
                set.objects.push_back({});
                o = &set.objects.back();
                o->objectId = id;
                o->name = m.value("name", "");
            }
            o->byTarget[m.at("target").get<std::string>()] = std::move(model);
        }
    } catch (const nlohmann::json::exception& e) {
        throw InputError(indexPath, "", std::string("malformed model index: ") + e.what());
    }
    return set;
}

}  // namespace rrf
