#include "core/nn/object_network_overrides.h"

#include "core/nn/encoding.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/encoding_settings_json.h"
#include "core/nn/network_settings.h"
#include "core/util/error.h"

namespace rrf {

nlohmann::json ObjectNetworkOverride::toJson() const {
    nlohmann::json j = nlohmann::json::object();
    if (hidden) j["hidden"] = *hidden;
    if (inputs) j["inputs"] = inputs->toJson();
    if (encoding) j["encoding"] = encodingSettingsJson(*encoding);
    return j;
}

ObjectNetworkChoice objectNetworkChoice(const ObjectNetworkChoice& base, const ObjectNetworkOverrides& overrides,
                                        const std::string& name) {
    ObjectNetworkChoice c = base;
    const auto it = overrides.find(name);
    if (it == overrides.end()) return c;
    const ObjectNetworkOverride& o = it->second;
    if (o.hidden) c.hidden = *o.hidden;
    if (o.inputs) c.inputs = *o.inputs;
    if (o.encoding) c.encoding = *o.encoding;
    return c;
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
        if (const auto inputs = entry.find("inputs")) o.inputs = DerivedInputs::fromJson(*inputs);
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
        if (!o.empty()) j[name] = o.toJson();
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

namespace {
template <typename Field>
void dropOverrides(ObjectNetworkOverrides& overrides, Field field) {
    for (auto it = overrides.begin(); it != overrides.end();) {
        (it->second.*field).reset();
        it = it->second.empty() ? overrides.erase(it) : std::next(it);
    }
}
}  // namespace

void dropHiddenOverrides(ObjectNetworkOverrides& overrides) { dropOverrides(overrides, &ObjectNetworkOverride::hidden); }
void dropInputsOverrides(ObjectNetworkOverrides& overrides) { dropOverrides(overrides, &ObjectNetworkOverride::inputs); }
void dropEncodingOverrides(ObjectNetworkOverrides& overrides) {
    dropOverrides(overrides, &ObjectNetworkOverride::encoding);
}

}  // namespace rrf
