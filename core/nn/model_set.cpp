#include "core/nn/model_set.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

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

namespace {

using nlohmann::json;

/// NaN (a node without validation records) has no JSON spelling: null and back.
json num(double d) { return std::isfinite(d) ? json(d) : json(nullptr); }
double num(const json& j) { return j.is_number() ? j.get<double>() : std::numeric_limits<double>::quiet_NaN(); }

json treeJson(const PartitionTree& t) {
    json nodes = json::array();
    for (const PartitionNode& n : t.nodes) {
        json j = {{"records", n.records}, {"error", num(n.error)}};
        if (n.isLeaf()) {
            j["leaf"] = n.leaf;
        } else {
            // A float widened to double prints with enough digits to read back the same float.
            j["axis"] = n.axis;
            j["split"] = double(n.split);
            j["left"] = n.left;
            j["right"] = n.right;
        }
        nodes.push_back(j);
    }
    return {{"nodes", nodes}};
}

PartitionTree treeFromJson(const json& j) {
    PartitionTree t;
    for (const json& n : j.at("nodes")) {
        PartitionNode x;
        x.records = n.at("records").get<int64_t>();
        x.error = num(n.at("error"));
        if (n.contains("leaf")) {
            x.leaf = n.at("leaf").get<int>();
        } else {
            x.axis = n.at("axis").get<int>();
            if (x.axis < 0) throw std::invalid_argument("negative split axis");
            x.split = float(n.at("split").get<double>());
            x.left = n.at("left").get<int>();
            x.right = n.at("right").get<int>();
        }
        t.nodes.push_back(x);
    }
    return t;
}

}  // namespace

nlohmann::json saveModelSet(const std::string& dir, const std::vector<ObjectModel>& trained, uint64_t sceneHash,
                            const std::vector<std::string>& inputLayout, const nlohmann::json& extra) {
    makeDirectories(dir);
    nlohmann::json index = extra.is_object() ? extra : nlohmann::json::object();
    index["format"] = "rrf-models";
    index["version"] = kModelSetVersion;
    index["scene_hash"] = hexString(sceneHash);
    index["input_layout"] = inputLayout;
    nlohmann::json models = nlohmann::json::array();
    for (const ObjectModel& m : trained) {
        if (m.skipped) {
            models.push_back({{"object", m.objectId}, {"name", m.objectName}, {"target", m.target}, {"skipped", m.message}});
            continue;
        }
        m.model.validate();
        const PartitionedNetwork& p = m.model;
        const std::vector<int> leafNodes = p.tree.leafNodes();
        nlohmann::json leaves = nlohmann::json::array();
        int epochs = 0;
        double seconds = 0;
        for (int l = 0; l < p.leafCount(); ++l) {
            const NetworkModel& net = p.leaves[size_t(l)];
            const std::string file = p.leafCount() == 1 ? modelFileName(m.objectId, m.target)
                                                        : leafModelFileName(m.objectId, m.target, l);
            saveModel(net, (fs::path(dir) / file).string());
            const PartitionNode& n = p.tree.nodes[size_t(leafNodes[size_t(l)])];
            leaves.push_back({{"file", file},
                              {"records", n.records},
                              {"error", num(n.error)},
                              {"rmse", {{"train", num(net.errors.train)}, {"validation", num(net.errors.validation)},
                                        {"test", num(net.errors.test)}}}});
            epochs += net.training.epochs;
            seconds += net.training.seconds;
        }
        models.push_back({{"object", m.objectId},
                          {"name", m.objectName},
                          {"target", m.target},
                          {"architecture", p.arch().describe()},
                          {"parameters", p.numParams()},
                          {"leaf_count", p.leafCount()},
                          {"depth", p.tree.depth()},
                          {"epochs", epochs},
                          {"seconds", seconds},
                          {"tree", treeJson(p.tree)},
                          {"leaves", leaves}});
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
    std::string where;  // JSON pointer of the model entry being read, for messages
    try {
        const int version = set.index.contains("version") ? set.index.at("version").get<int>() : 1;
        if (version < 1 || version > kModelSetVersion)
            throw InputError(indexPath, "/version", "model index version " + std::to_string(version) +
                                                        " is not supported (this build reads 1 … " +
                                                        std::to_string(kModelSetVersion) + ")");
        set.sceneHash = std::stoull(set.index.at("scene_hash").get<std::string>(), nullptr, 16);
        set.inputLayout = set.index.at("input_layout").get<std::vector<std::string>>();
        if (expectedSceneHash != 0 && set.sceneHash != expectedSceneHash)
            throw InputError(indexPath, "/scene_hash", "these models were trained for a different scene: retrain them for this project");
        const nlohmann::json& models = set.index.at("models");
        for (size_t i = 0; i < models.size(); ++i) {
            const nlohmann::json& m = models[i];
            where = "/models/" + std::to_string(i);
            if (m.contains("skipped")) continue;
            // Version 1: one network per model ("file"); version 2: a tree and its leaves' files.
            std::vector<std::string> files;
            PartitionTree tree;
            if (m.contains("tree")) {
                tree = treeFromJson(m.at("tree"));
                for (const nlohmann::json& l : m.at("leaves")) files.push_back(l.at("file").get<std::string>());
            } else {
                files.push_back(m.at("file").get<std::string>());
            }
            PartitionedNetwork model;
            for (const std::string& f : files) {
                const std::string file = (fs::path(dir) / f).string();
                NetworkModel net = loadModel(file);
                if (net.arch.inputs != int(set.inputLayout.size()))
                    throw InputError(file, "", "network has " + std::to_string(net.arch.inputs) + " inputs but the index lists " +
                                                   std::to_string(set.inputLayout.size()));
                model.leaves.push_back(std::move(net));
            }
            model.tree = m.contains("tree") ? std::move(tree) : PartitionedNetwork(model.leaves.front()).tree;
            try {
                model.validate();
            } catch (const std::invalid_argument& e) {
                throw InputError(indexPath, where + "/tree", e.what());
            }
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
        throw InputError(indexPath, where, std::string("malformed model index: ") + e.what());
    } catch (const std::invalid_argument& e) {
        throw InputError(indexPath, where, std::string("malformed model index: ") + e.what());
    }
    return set;
}

}  // namespace rrf
