#include "core/nn/network_settings_json.h"

#include "core/nn/derived_inputs_json.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/encoding_settings_json.h"
#include "core/nn/object_network_overrides_json.h"
#include "core/util/error.h"

namespace rrf {

std::vector<int> hiddenSizesFromJson(const JsonReader& hidden) {
    if (hidden.requireArray() == 0) hidden.fail("expected a non-empty array of layer sizes");
    std::vector<int> sizes;
    for (size_t i = 0; i < hidden.value().size(); ++i) sizes.push_back(int(hidden.at(i).integer(1, kMaxHiddenSize)));
    return sizes;
}

NetworkSettings networkSettingsFromJson(const JsonReader& r, const NetworkSettings& base,
                                        const std::vector<std::string>* sceneObjects) {
    NetworkSettings s = base;
    r.checkKeys(NetworkSettings::keys());
    if (const auto hidden = r.find("hidden")) s.options.hidden = hiddenSizesFromJson(*hidden);
    s.options.activation = parseActivation(r.choiceOr("activation", activationName(s.options.activation), {"tanh", "relu"}));
    s.options.ensemble = int(r.integerOr("ensemble", s.options.ensemble, 1, kMaxEnsembleMembers));
    if (const auto inputs = r.find("inputs")) s.options.inputs = derivedInputsFromJson(*inputs);
    if (const auto encoding = r.find("encoding")) {
        // Checked as every network will build it (errors name the file and the pointer of the bad
        // value); kept as a setting, since each network builds it for its own records' input count.
        s.options.encoding = readEncodingSettingsFor(*encoding, kEncodingCheckInputs, s.options.inputs);
    } else if (r.has("inputs") && !s.options.encoding.empty()) {
        // `base`'s encoding must still fit the inputs this section sets.
        try {
            buildInputEncoding(s.options.encoding, kEncodingCheckInputs, s.options.inputs,
                               failAtPointer(r.file(), r.pointer() + "/encoding"));
        } catch (const InputError& e) {
            r.at("inputs").fail("the network's encoding reads an input these inputs do not have (" + e.detail() + ")");
        }
    }
    if (const auto objects = r.find("objects")) {
        s.options.perObject = objectOverridesFromJson(*objects, s.options.sharedChoice());
        if (sceneObjects) checkOverrideNames(*objects, *sceneObjects);
    }
    s.options.targets = parseTargetMode(r.choiceOr("targets", targetModeName(s.options.targets),
                                                   {"separate", "joint", "global", "direct", "indirect"}));
    if (const auto partition = r.find("partition")) s.options.partition = partitionFromJson(*partition, s.options.partition);
    return s;
}

nlohmann::json toJson(const NetworkSettings& s) {
    const NetworkOptions& options = s.options;
    return {{"hidden", options.hidden},
            {"activation", activationName(options.activation)},
            {"ensemble", options.ensemble},
            {"inputs", toJson(options.inputs)},
            {"encoding", encodingSettingsJson(options.encoding)},
            {"objects", objectOverridesJson(options.perObject)},
            {"targets", targetModeName(options.targets)},
            {"partition", partitionJson(options.partition)}};
}

PartitionSettings partitionFromJson(const JsonReader& r, const PartitionSettings& base) {
    PartitionSettings p = base;
    r.requireObject();
    r.checkKeys({"goal", "max_depth", "max_leaves", "min_records_per_weight", "min_split_gain", "split_axes"});
    p.goal = r.numberOr("goal", p.goal, 0.0, 10.0, true);
    p.maxDepth = int(r.integerOr("max_depth", p.maxDepth, 0, 20));
    p.maxLeaves = int(r.integerOr("max_leaves", p.maxLeaves, 1, kMaxPartitionLeaves));
    p.minRecordsPerWeight = r.numberOr("min_records_per_weight", p.minRecordsPerWeight, 1.0, 1000.0);
    p.minSplitGain = r.numberOr("min_split_gain", p.minSplitGain, 0.0, 0.99);
    if (const auto axes = r.find("split_axes")) {
        const size_t n = axes->requireArray();
        if (n == 0) axes->fail("expected a non-empty array of \"position\" and/or \"light\"");
        p.axes = PartitionAxes{false, false};
        for (size_t i = 0; i < n; ++i) {
            const JsonReader a = axes->at(i);
            try {
                PartitionAxes::enable(p.axes, a.string());
            } catch (const std::invalid_argument& e) {
                a.fail(e.what());
            }
        }
    }
    return p;
}

nlohmann::json partitionJson(const PartitionSettings& p) {
    return {{"goal", p.goal},
            {"max_depth", p.maxDepth},
            {"max_leaves", p.maxLeaves},
            {"min_records_per_weight", p.minRecordsPerWeight},
            {"min_split_gain", p.minSplitGain},
            {"split_axes", p.axes.names()}};
}

}  // namespace rrf
