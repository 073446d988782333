#include "core/nn/network_settings.h"

#include "core/nn/encoding_presets.h"
#include "core/nn/encoding_settings_json.h"

#include <sstream>

#include "core/util/error.h"
#include "core/util/json_reader.h"

namespace rrf {

std::vector<int> parseHiddenSizes(const std::string& text, const std::string& setting) {
    std::vector<int> sizes;
    std::istringstream in(text);
    std::string part;
    while (std::getline(in, part, ',')) {
        try {
            size_t used = 0;
            const int v = std::stoi(part, &used);
            if (used != part.size() || v < 1 || v > kMaxHiddenSize) throw std::invalid_argument(part);
            sizes.push_back(v);
        } catch (const std::exception&) {
            throw SettingError(setting, "expected comma-separated layer sizes in 1.." + std::to_string(kMaxHiddenSize) +
                                            " (e.g. 20,10), got '" + text + "'");
        }
    }
    if (sizes.empty()) throw SettingError(setting, "expected at least one hidden layer size, got '" + text + "'");
    return sizes;
}

std::string hiddenSizesText(const std::vector<int>& sizes) {
    std::string t;
    for (size_t i = 0; i < sizes.size(); ++i) t += (i ? "," : "") + std::to_string(sizes[i]);
    return t;
}

std::vector<int> hiddenSizesFromJson(const JsonReader& hidden) {
    if (hidden.requireArray() == 0) hidden.fail("expected a non-empty array of layer sizes");
    std::vector<int> sizes;
    for (size_t i = 0; i < hidden.value().size(); ++i) sizes.push_back(int(hidden.at(i).integer(1, kMaxHiddenSize)));
    return sizes;
}

const std::vector<std::string>& NetworkSettings::keys() {
    static const std::vector<std::string> k = {"hidden",  "activation", "ensemble", "inputs",
                                               "encoding", "objects",   "targets",  "partition"};
    return k;
}

NetworkSettings NetworkSettings::fromJson(const JsonReader& r, const NetworkSettings& base,
                                          const std::vector<std::string>* sceneObjects) {
    NetworkSettings s = base;
    r.checkKeys(keys());
    if (const auto hidden = r.find("hidden")) s.options.hidden = hiddenSizesFromJson(*hidden);
    s.options.activation = parseActivation(r.choiceOr("activation", activationName(s.options.activation), {"tanh", "relu"}));
    s.options.ensemble = int(r.integerOr("ensemble", s.options.ensemble, 1, kMaxEnsembleMembers));
    if (const auto inputs = r.find("inputs")) s.options.inputs = DerivedInputs::fromJson(*inputs);
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

nlohmann::json NetworkSettings::networkJson() const {
    return {{"hidden", options.hidden},
            {"activation", activationName(options.activation)},
            {"ensemble", options.ensemble},
            {"inputs", options.inputs.toJson()},
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
