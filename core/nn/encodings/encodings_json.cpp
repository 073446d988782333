#include "core/nn/encodings/encodings_json.h"

#include <stdexcept>
#include <string>
#include <variant>

#include "core/nn/encodings/frequency.h"
#include "core/nn/encodings/hash_grid.h"
#include "core/nn/encodings/one_blob.h"

namespace rrf {

FrequencySettings frequencySettingsFromJson(const JsonReader& r) {
    FrequencySettings s;
    s.frequencies = int(r.integerOr("frequencies", s.frequencies, 1, FrequencyEncoding::kMaxFrequencies));
    s.includeInput = r.booleanOr("include_input", s.includeInput);
    return s;
}

OneBlobSettings oneBlobSettingsFromJson(const JsonReader& r) {
    OneBlobSettings s;
    s.bins = int(r.integerOr("bins", s.bins, OneBlobEncoding::kMinBins, OneBlobEncoding::kMaxBins));
    return s;
}

HashGridSettings hashGridSettingsFromJson(const JsonReader& r) {
    using H = HashGridEncoding;
    HashGridSettings s;
    s.levels = int(r.integerOr("levels", s.levels, 1, H::kMaxLevels));
    s.log2TableSize = int(r.integerOr("log2_table_size", s.log2TableSize, H::kMinLog2TableSize, H::kMaxLog2TableSize));
    if (const auto f = r.find("features_per_level")) {
        s.featuresPerLevel = int(f->integer(1, 8));
        if (s.featuresPerLevel & (s.featuresPerLevel - 1)) f->fail("expected 1, 2, 4 or 8, got " + std::to_string(s.featuresPerLevel));
    }
    s.baseResolution = int(r.integerOr("base_resolution", s.baseResolution, H::kMinBaseResolution, H::kMaxBaseResolution));
    s.growth = r.numberOr("growth", s.growth, 1.0, H::kMaxGrowth);
    try {
        // The combination (finest resolution, table bytes) does not depend on the input count, which
        // the reader does not know yet (the builder checks it against the type's maxInputs).
        (void)HashGridEncoding(1, s);
    } catch (const std::invalid_argument& e) {
        r.fail(e.what());
    }
    return s;
}

EncodingParams encodingParamsFromJson(const EncodingType& type, const JsonReader& component) {
    // One reader per alternative of EncodingParams, in encodingTypes() order (encodings/encoding_params.h).
    static_assert(std::variant_size_v<EncodingParams> == 3, "a new encoding type needs its reader here");
    if (&type == &FrequencyEncoding::type()) return frequencySettingsFromJson(component);
    if (&type == &OneBlobEncoding::type()) return oneBlobSettingsFromJson(component);
    if (&type == &HashGridEncoding::type()) return hashGridSettingsFromJson(component);
    throw std::invalid_argument(std::string("encoding type '") + type.name + "' has no JSON reader");
}

nlohmann::json toJson(const FrequencySettings& s) {
    return {{"frequencies", s.frequencies}, {"include_input", s.includeInput}};
}

nlohmann::json toJson(const OneBlobSettings& s) { return {{"bins", s.bins}}; }

nlohmann::json toJson(const HashGridSettings& s) {
    return {{"levels", s.levels},
            {"log2_table_size", s.log2TableSize},
            {"features_per_level", s.featuresPerLevel},
            {"base_resolution", s.baseResolution},
            {"growth", s.growth}};
}

nlohmann::json toJson(const EncodingParams& params) {
    return std::visit([](const auto& s) { return toJson(s); }, params);
}

}  // namespace rrf
