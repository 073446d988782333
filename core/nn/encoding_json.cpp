#include "core/nn/encoding_json.h"

#include "core/nn/encoding_settings_json.h"
#include "core/nn/encodings/encodings_json.h"

namespace rrf {

InputEncoding inputEncodingFromJson(const JsonReader& r, int inputs, const DerivedInputs& derived) {
    return buildInputEncoding(readEncodingSettings(r), inputs, derived, failAtReader(r));
}

nlohmann::json toJson(const InputEncoding& encoding) {
    nlohmann::json a = nlohmann::json::array();
    for (const EncodingComponent& c : encoding.components) {
        nlohmann::json j = toJson(c.encoding->params());
        j["type"] = c.encoding->typeName();
        j["inputs"] = c.groups.size() == 1 ? nlohmann::json(c.groups[0]) : nlohmann::json(c.groups);
        a.push_back(std::move(j));
    }
    return a;
}

}  // namespace rrf
