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
/// load, unverified. The set's files are read and written in nn/model_set_file.cpp.

#include <map>
#include <string>
#include <vector>

#include "core/nn/model.h"
#include "core/nn/network_settings.h"
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
    /// models.json's "index_checksum64" as read ("" for an index older than version 3): it names this
    /// set's exact networks (an evaluation records which models it measured).
    std::string indexChecksum;
    const ObjectNetworks* find(int objectId) const;
};

/// Version of models.json written by saveModelSet (1: one network per model; 2: kd-trees;
/// 3: checksums of the index and of every model file).
constexpr int kModelSetVersion = 3;

/// Where a set's networks came from and how they were trained, written into models.json beside them
/// ("dataset", "project", "network", "trainer", "seconds", "cancelled"; nn/training_run.h).
struct ModelSetRecord {
    std::string dataset;      ///< the dataset file the samples were read from
    std::string project;      ///< the project (or bare scene) file the settings came from
    NetworkSettings network;  ///< the "network" section the networks were built with
    TrainerConfig trainer;    ///< the "trainer" section they were trained with
    double seconds = 0.0;     ///< wall time of the training run
    bool cancelled = false;   ///< the run was cancelled before every network finished
};

/// Replaces directory `dir` (created if missing) with a set holding every non-skipped model of
/// `trained` and the index, as a whole: the previous set's models.json and *.rrfm files go, other
/// files in `dir` are kept. `record` (may be null) is written into models.json too.
void saveModelSet(const std::string& dir, const std::vector<ObjectModel>& trained, uint64_t sceneHash,
                  const std::vector<std::string>& inputLayout, const ModelSetRecord* record = nullptr);

/// Loads a model directory. `expectedSceneHash` ≠ 0 rejects models trained for another scene.
/// Throws InputError / std::runtime_error naming the file.
ModelSet loadModelSet(const std::string& dir, uint64_t expectedSceneHash = 0);

}  // namespace rrf
