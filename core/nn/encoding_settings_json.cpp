#include "core/nn/encoding_settings_json.h"

#include <algorithm>

#include "core/nn/encodings/encodings_json.h"
#include "core/nn/encodings/registry.h"
#include "core/util/error.h"

namespace rrf {

namespace {

/// Keys a component object of type `t` may have: "type", "inputs" and its hyperparameters.
std::vector<std::string> componentKeys(const EncodingType& t) {
    std::vector<std::string> keys = {"type", "inputs"};
    keys.insert(keys.end(), t.keys.begin(), t.keys.end());
    return keys;
}

EncodingSettings readComponent(const JsonReader& cr) {
    cr.requireObject();
    const JsonReader typeReader = cr.at("type");
    const std::string typeName = typeReader.string();
    const EncodingType* type = findEncodingType(typeName);
    if (!type) typeReader.fail("unknown encoding type '" + typeName + "' (expected " + encodingTypeNames() + ")");
    cr.checkKeys(componentKeys(*type));

    EncodingSettings c;
    const JsonReader in = cr.at("inputs");
    if (in.value().is_string()) {
        c.groups.push_back(in.string());
    } else {
        if (!in.isArray()) in.fail("expected an input group name or an array of them, got " + JsonReader::describe(in.value()));
        if (in.requireArray() == 0) in.fail("expected at least one input group");
        c.groupsListed = true;
        for (size_t g = 0; g < in.value().size(); ++g) c.groups.push_back(in.at(g).string());
    }
    c.params = encodingParamsFromJson(*type, cr);
    for (const std::string& key : type->keys)
        if (cr.has(key)) c.keys.push_back(key);
    std::sort(c.keys.begin(), c.keys.end());
    return c;
}

}  // namespace

NetworkEncodingSettings readEncodingSettings(const JsonReader& r) {
    const size_t count = r.requireArray();
    NetworkEncodingSettings s;
    for (size_t k = 0; k < count; ++k) s.push_back(readComponent(r.at(k)));
    return s;
}

EncodingFault failAtPointer(const std::string& file, const std::string& pointer) {
    return [file, pointer](const std::string& at, const std::string& what) { throw InputError(file, pointer + at, what); };
}

NetworkEncodingSettings readEncodingSettingsFor(const JsonReader& r, int inputs, const DerivedInputs& derived) {
    NetworkEncodingSettings s = readEncodingSettings(r);
    buildInputEncoding(s, inputs, derived, failAtReader(r));
    return s;
}

nlohmann::json encodingSettingsJson(const NetworkEncodingSettings& s) {
    nlohmann::json a = nlohmann::json::array();
    for (const EncodingSettings& c : s) {
        const nlohmann::json every = toJson(c.params);
        nlohmann::json j = nlohmann::json::object();
        for (const std::string& key : c.keys) j[key] = every.at(key);
        j["type"] = c.type().name;
        j["inputs"] = c.groupsListed || c.groups.size() != 1 ? nlohmann::json(c.groups) : nlohmann::json(c.groups.at(0));
        a.push_back(std::move(j));
    }
    return a;
}

NetworkEncodingSettings encodingSettingsFromJson(const nlohmann::json& encoding, const std::string& file) {
    return readEncodingSettings(JsonReader(encoding, file, ""));
}

}  // namespace rrf
