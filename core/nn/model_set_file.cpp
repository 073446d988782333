// The model set's files (format in nn/model_set.h): models.json and the model files it lists.
#include "core/nn/model_set.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "core/data/dataset_file.h"
#include "core/nn/network_settings_json.h"
#include "core/nn/trainer_config_json.h"
#include "core/util/atomic_file.h"
#include "core/util/directory_replace.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "core/util/staged_files.h"
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

constexpr int64_t kMaxInt = std::numeric_limits<int>::max();

/// Typed reads (core/util/json_reader.h): 1e300 in an integer field is an InputError naming it.
PartitionTree treeFromJson(const JsonReader& j) {
    PartitionTree t;
    const JsonReader nodes = j.at("nodes");
    for (size_t i = 0, count = nodes.requireArray(); i < count; ++i) {
        const JsonReader n = nodes.at(i);
        PartitionNode x;
        x.records = n.at("records").integer(0, int64_t(1) << 62);  // 2^62: exact as a double, unlike INT64_MAX
        x.error = num(n.at("error").value());
        if (n.has("leaf")) {
            x.leaf = int(n.at("leaf").integer(0, kMaxInt));
        } else {
            x.axis = int(n.at("axis").integer(0, kMaxInt));
            x.split = n.at("split").floatValue();
            x.left = int(n.at("left").integer(0, kMaxInt));
            x.right = int(n.at("right").integer(0, kMaxInt));
        }
        t.nodes.push_back(x);
    }
    return t;
}

/// models.json's own checksum: checksum64 of the file's text with the field's 16 hex digits read
/// as zeros. Being computed over the exact bytes, it also covers formatting the parser would ignore.
constexpr const char* kIndexChecksumKey = "\"index_checksum64\": \"";
constexpr size_t kHexDigits = 16;

/// Where the checksum's digits start in `text`, or npos if the field is absent.
size_t indexChecksumAt(const std::string& text) {
    const size_t at = text.find(kIndexChecksumKey);
    if (at == std::string::npos) return at;
    const size_t digits = at + std::strlen(kIndexChecksumKey);
    return digits + kHexDigits <= text.size() ? digits : std::string::npos;
}

uint64_t indexChecksum(std::string text, size_t digits) {
    text.replace(digits, kHexDigits, kHexDigits, '0');
    return checksum64(text.data(), text.size());
}

/// Members of a model set's directory (replaced with it); anything else there is kept.
bool isModelSetEntry(const std::string& name) {
    auto endsWith = [&](const std::string& tail) {
        return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
    };
    return name == "models.json" || endsWith(".rrfm");
}

}  // namespace

void saveModelSet(const std::string& dir, const std::vector<ObjectModel>& trained, uint64_t sceneHash,
                  const std::vector<std::string>& inputLayout, const ModelSetRecord* record) {
    nlohmann::json index = nlohmann::json::object();
    if (record)
        index = {{"dataset", record->dataset},       {"project", record->project},
                 {"network", toJson(record->network)}, {"trainer", toJson(record->trainer)},
                 {"seconds", record->seconds},         {"cancelled", record->cancelled}};
    for (const ObjectModel& m : trained)
        if (!m.skipped) m.model.validate();
    // The whole set goes into a new directory that replaces the old one in one rename
    // (core/util/directory_replace.h): a kill or a full disk leaves the old set or the new one.
    replaceDirectory(dir, isModelSetEntry, [&](const std::string& staging) {
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
            const PartitionedNetwork& p = m.model;
            const std::vector<int> leafNodes = p.tree.leafNodes();
            nlohmann::json leaves = nlohmann::json::array();
            int epochs = 0;
            double seconds = 0;
            for (int l = 0; l < p.leafCount(); ++l) {
                const NetworkModel& net = p.leaves[size_t(l)];
                const std::string file = p.leafCount() == 1 ? modelFileName(m.objectId, m.target)
                                                            : leafModelFileName(m.objectId, m.target, l);
                // Written plainly into the staging directory, which replaceDirectory syncs as a
                // whole: a per-file fsync and rename made saving many leaves take seconds.
                const std::string bytes = modelFileBytes(net);
                writeStagedFile((fs::path(staging) / file).string(), bytes);
                // The file's size and checksum tie it to this index: a file changed afterwards, or
                // copied in from another set, no longer matches.
                const PartitionNode& n = p.tree.nodes[size_t(leafNodes[size_t(l)])];
                leaves.push_back({{"file", file},
                                  {"bytes", bytes.size()},
                                  {"checksum64", hexString16(checksum64(bytes.data(), bytes.size()))},
                                  {"records", n.records},
                                  {"error", num(n.error)},
                                  {"rmse", {{"train", num(net.errors.train)}, {"validation", num(net.errors.validation)},
                                            {"test", num(net.errors.test)}}}});
                epochs += net.training.memberEpochs;  // every ensemble member's epochs
                seconds += net.training.seconds;
            }
            models.push_back({{"object", m.objectId},
                              {"name", m.objectName},
                              {"target", m.target},
                              {"architecture", p.arch().describe()},
                              {"encoding", p.encoding().describe()},
                              {"parameters", p.numParams()},
                              {"leaf_count", p.leafCount()},
                              {"depth", p.tree.depth()},
                              {"epochs", epochs},
                              {"seconds", seconds},
                              {"tree", treeJson(p.tree)},
                              {"leaves", leaves}});
        }
        index["models"] = models;
        index["index_checksum64"] = std::string(kHexDigits, '0');
        // NaN errors (empty validation sets) are not valid JSON numbers: nlohmann writes null for them.
        std::string text = index.dump(2) + "\n";
        const size_t digits = indexChecksumAt(text);
        const std::string sum = hexString16(indexChecksum(text, digits));
        text.replace(digits, kHexDigits, sum);
        index["index_checksum64"] = sum;
        writeStagedFile((fs::path(staging) / "models.json").string(), text);
    });
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
    // The checksum goes first: a changed byte is reported as such, not as whatever it broke.
    const size_t digits = indexChecksumAt(text);
    if (digits != std::string::npos && text.compare(digits, kHexDigits, hexString16(indexChecksum(text, digits))) != 0)
        throw InputError(indexPath, "/index_checksum64",
                         "checksum mismatch: the index was changed or damaged after it was written (train the models again)");
    nlohmann::json indexJson;
    try {
        indexJson = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(indexPath, "", std::string("malformed JSON: ") + e.what());
    }
    const JsonReader index(indexJson, indexPath);
    index.requireObject();
    if (const auto sum = index.find("index_checksum64"); sum && sum->value().is_string()) set.indexChecksum = sum->string();
    const int version = index.has("version") ? int(index.at("version").integer(1, kMaxInt)) : 1;
    if (version > kModelSetVersion)
        throw InputError(indexPath, "/version", "model index version " + std::to_string(version) +
                                                    " is not supported (this build reads 1 … " +
                                                    std::to_string(kModelSetVersion) + ")");
    // From version 3 every index carries its checksum and every file's; older ones load unverified.
    const bool verified = version >= 3;
    if (verified && digits == std::string::npos)
        throw InputError(indexPath, "/index_checksum64", "missing: a version 3 index carries its own checksum");
    const std::string hash = index.at("scene_hash").string();
    if (hash.empty() || hash.size() > kHexDigits || hash.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
        throw InputError(indexPath, "/scene_hash", "expected up to 16 hex digits, got \"" + hash + "\"");
    set.sceneHash = std::stoull(hash, nullptr, 16);
    const JsonReader layout = index.at("input_layout");
    for (size_t i = 0, n = layout.requireArray(); i < n; ++i) set.inputLayout.push_back(layout.at(i).string());
    if (expectedSceneHash != 0 && set.sceneHash != expectedSceneHash)
        throw InputError(indexPath, "/scene_hash", "these models were trained for a different scene: retrain them for this project");
    const JsonReader models = index.at("models");
    for (size_t i = 0, count = models.requireArray(); i < count; ++i) {
        const JsonReader m = models.at(i);
        if (m.has("skipped")) continue;
        const int id = int(m.at("object").integer(0, kMaxInt));
        const std::string target = m.at("target").string();
        // Version 1: one network per model ("file"); version 2 on: a tree and its leaves' files.
        std::vector<std::pair<std::string, JsonReader>> files;
        PartitionTree tree;
        if (m.has("tree")) {
            tree = treeFromJson(m.at("tree"));
            const JsonReader leaves = m.at("leaves");
            for (size_t l = 0, n = leaves.requireArray(); l < n; ++l)
                files.emplace_back(leaves.at(l).at("file").string(), leaves.at(l));
        } else {
            files.emplace_back(m.at("file").string(), m);
        }
        PartitionedNetwork model;
        for (const auto& [name, entry] : files) {
            // A bare file name: an index must not reach outside its own directory.
            if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
                throw InputError(indexPath, entry.pointer() + "/file", "expected a file name in the model directory, got \"" + name + "\"");
            const std::string file = (fs::path(dir) / name).string();
            std::string bytes;
            try {
                bytes = readFile(file);
            } catch (const std::exception&) {
                throw InputError(file, "", "missing: listed in " + indexPath + " at " + entry.pointer() + "/file");
            }
            if (verified) {
                const uint64_t size = entry.at("bytes").unsignedInteger();
                const std::string sum = entry.at("checksum64").string();
                if (size != bytes.size() || sum != hexString16(checksum64(bytes.data(), bytes.size())))
                    throw InputError(file, "", "does not match " + indexPath + " (" + entry.pointer() +
                                                   "/checksum64): the file was changed or belongs to another model set");
            }
            NetworkModel net = parseModel(bytes, file);
            if (net.rawInputs() != int(set.inputLayout.size()))
                throw InputError(file, "", "network has " + std::to_string(net.rawInputs()) + " inputs but the index lists " +
                                               std::to_string(set.inputLayout.size()));
            if (net.objectId != id || net.target != target)
                throw InputError(file, "", "holds the " + net.target + " network of object " + std::to_string(net.objectId) +
                                               ", but " + indexPath + " lists it at " + m.pointer() + " for the " + target +
                                               " network of object " + std::to_string(id));
            model.leaves.push_back(std::move(net));
        }
        if (model.leaves.empty()) throw InputError(indexPath, m.pointer() + "/leaves", "expected at least one network");
        model.tree = m.has("tree") ? std::move(tree) : PartitionedNetwork(model.leaves.front()).tree;
        try {
            model.validate();
        } catch (const std::invalid_argument& e) {
            throw InputError(indexPath, m.pointer() + "/tree", e.what());
        }
        ObjectNetworks* o = nullptr;
        for (ObjectNetworks& x : set.objects)
            if (x.objectId == id) o = &x;
        if (!o) {
            set.objects.push_back({});
            o = &set.objects.back();
            o->objectId = id;
            o->name = m.stringOr("name", "");
        }
        o->byTarget[target] = std::move(model);
    }
    return set;
}

}  // namespace rrf
