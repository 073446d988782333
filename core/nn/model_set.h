#pragma once
/// A directory of trained networks for one scene: per object and target one model file
/// (nn/object_training.h's modelFileName), or one per leaf when the model is partitioned
/// (leafModelFileName), plus `models.json`, the index that records the scene hash, the dataset, the
/// record layout, each model's kd-tree and which file holds which network. Prediction loads the set
/// and refuses models made for another scene or another input layout.
///
/// Index version 3 (this build) stores per model "tree": {"nodes": [...]} (nn/partition_tree.h's
/// nodes: axis, split, left, right, leaf, records, error) and "leaves": [{"file", "bytes",
/// "checksum64", "records", "error"}, ...], plus "index_checksum64", the checksum of models.json
/// itself. The set is written as a whole (core/util/directory_replace.h) and the loader refuses a
/// changed index and any file that is missing, changed or from another set, naming it. Version 2
/// indexes (no checksums) and version 1 (one "file" per model, loading as single-leaf trees) still
/// load, unverified.

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/nn/model.h"
#include "core/nn/object_training.h"
#include "core/scene/scene.h"

namespace rrf {

/// Networks of one object: either a joint 6-output net, a global net, or direct and/or indirect nets,
/// each a kd-tree of networks (a single leaf when not partitioned).
struct ObjectNetworks {
    int objectId = -1;
    std::string name;
    std::map<std::string, PartitionedNetwork> byTarget;  ///< "direct", "indirect", "global" or "joint"
    bool has(const std::string& t) const { return byTarget.count(t) != 0; }
};

struct ModelSet {
    std::string dir;
    uint64_t sceneHash = 0;
    std::vector<std::string> inputLayout;
    std::vector<ObjectNetworks> objects;  ///< objects with at least one network
    nlohmann::json index;                 ///< models.json as read
    const ObjectNetworks* find(int objectId) const;
};

/// Version of models.json written by saveModelSet (1: one network per model; 2: kd-trees;
/// 3: checksums of the index and of every model file).
constexpr int kModelSetVersion = 3;

/// Replaces directory `dir` (created if missing) with a set holding every non-skipped model of
/// `trained` and the index, as a whole: the previous set's models.json and *.rrfm files go, other
/// files in `dir` are kept. `extra` is merged into models.json (dataset path, settings, timings).
/// Returns the index.
nlohmann::json saveModelSet(const std::string& dir, const std::vector<ObjectModel>& trained, uint64_t sceneHash,
                            const std::vector<std::string>& inputLayout, const nlohmann::json& extra = {});

/// Loads a model directory. `expectedSceneHash` ≠ 0 rejects models trained for another scene.
/// Throws InputError / std::runtime_error naming the file.
ModelSet loadModelSet(const std::string& dir, uint64_t expectedSceneHash = 0);

}  // namespace rrf
