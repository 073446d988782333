#include "core/nn/object_network_overrides_json.h"

#include "core/nn/derived_inputs_json.h"
#include "core/nn/encoding.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/encoding_settings_json.h"
#include "core/nn/network_settings_json.h"
#include "core/util/error.h"

namespace rrf {

nlohmann::json toJson(const ObjectNetworkOverride& o) {
    nlohmann::json j = nlohmann::json::object();
    if (o.hidden) j["hidden"] = *o.hidden;
    if (o.inputs) j["inputs"] = toJson(*o.inputs);
    if (o.encoding) j["encoding"] = encodingSettingsJson(*o.encoding);
    return j;
}

ObjectNetworkOverrides objectOverridesFromJson(const JsonReader& objects, const ObjectNetworkChoice& base) {
    objects.requireObject();
    ObjectNetworkOverrides out;
    for (auto it = objects.value().begin(); it != objects.value().end(); ++it) {
        const JsonReader entry = objects.at(it.key());
        entry.requireObject();
        entry.checkKeys({"hidden", "inputs", "encoding"});
        ObjectNetworkOverride o;
        if (const auto hidden = entry.find("hidden")) o.hidden = hiddenSizesFromJson(*hidden);
        if (const auto inputs = entry.find("inputs")) o.inputs = derivedInputsFromJson(*inputs);
        if (const auto encoding = entry.find("encoding")) {
            // Checked as this object's networks will read it: against the entry's inputs, else the section's.
            o.encoding = readEncodingSettingsFor(*encoding, kEncodingCheckInputs, o.inputs.value_or(base.inputs));
        } else if (o.inputs && !o.inputs->reflected && !base.encoding.empty()) {
            // The section's encoding must still fit an entry that turns a derived input off.
            try {
                buildInputEncoding(base.encoding, kEncodingCheckInputs, *o.inputs,
                                   failAtPointer(entry.file(), entry.pointer() + "/inputs"));
            } catch (const InputError& e) {
                entry.at("inputs").fail("the section's \"encoding\" reads an input this entry turns off (" + e.detail() +
                                        "); give the entry its own \"encoding\"");
            }
        }
        if (!o.empty()) out.emplace(it.key(), std::move(o));
    }
    return out;
}

nlohmann::json objectOverridesJson(const ObjectNetworkOverrides& overrides) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, o] : overrides)
        if (!o.empty()) j[name] = toJson(o);
    return j;
}

void requireSceneObjectName(const JsonReader& at, const std::string& name, const std::vector<std::string>& sceneObjects) {
    for (const std::string& n : sceneObjects)
        if (n == name) return;
    std::string list;
    for (const std::string& n : sceneObjects) list += (list.empty() ? "" : ", ") + ("\"" + n + "\"");
    at.fail("no object named \"" + name + "\" in the scene (expected one of " + list + ")");
}

void checkOverrideNames(const JsonReader& objects, const std::vector<std::string>& sceneObjects) {
    for (auto it = objects.value().begin(); it != objects.value().end(); ++it)
        requireSceneObjectName(objects.at(it.key()), it.key(), sceneObjects);
}

}  // namespace rrf
