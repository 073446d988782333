#include "core/nn/encoding_presets.h"

#include "core/nn/ensemble.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"

namespace rrf {

namespace {
using nlohmann::json;

/// instant-NGP's grid scaled to the radiance networks' data (about 10^4–10^5 records per object):
/// 8 levels from 4 to 4·1.5^7 ≈ 68 cells per axis, 2^12 entries of 2 features per level (65 536
/// parameters, 512 KiB as float64 per network), so a coarse level is dense and a fine one hashed.
json hashGridOverPosition() {
    return {{"type", "hash_grid"},      {"inputs", "position"},    {"levels", 8},  {"log2_table_size", 12},
            {"features_per_level", 2}, {"base_resolution", 4},     {"growth", 1.5}};
}
}  // namespace

const std::vector<EncodingPreset>& encodingPresets() {
    static const std::vector<EncodingPreset> presets = {
        {"raw", "the normalised inputs themselves (Ren et al. 2013)", json::array()},
        {"frequency", "sin/cos of 2^k*pi*x, k < 4, over position and light (NeRF), the rest raw",
         json::array({{{"type", "frequency"}, {"inputs", {"position", "light"}}, {"frequencies", 4}, {"include_input", true}}})},
        {"one_blob", "16 one-blob bins per input over position, view, light and normal (NRC), the rest raw",
         json::array({{{"type", "one_blob"}, {"inputs", {"position", "view", "light", "normal"}}, {"bins", 16}}})},
        {"hash_grid", "a trainable multiresolution hash grid over position (instant-NGP; adam only), the rest raw",
         json::array({hashGridOverPosition()})},
        {"hash_grid_one_blob", "the hash grid over position, 16 one-blob bins over view, light and normal (adam only)",
         json::array({hashGridOverPosition(),
                      {{"type", "one_blob"}, {"inputs", {"view", "light", "normal"}}, {"bins", 16}}})},
    };
    return presets;
}

const EncodingPreset* findEncodingPreset(const std::string& name) {
    for (const EncodingPreset& p : encodingPresets())
        if (name == p.name) return &p;
    return nullptr;
}

nlohmann::json encodingPresetSettings(const std::string& name, const std::string& setting) {
    if (const EncodingPreset* p = findEncodingPreset(name)) return p->settings;
    throw SettingError(setting, "unknown encoding '" + name + "' (expected one of " + encodingPresetNames(", ") + ")");
}

std::string encodingPresetNames(const char* separator) {
    std::string names;
    for (const EncodingPreset& p : encodingPresets()) names += (names.empty() ? "" : separator) + std::string(p.name);
    return names;
}

std::string encodingPresetName(const nlohmann::json& encoding) {
    const bool empty = encoding.is_null() || (encoding.is_array() && encoding.empty());
    for (const EncodingPreset& p : encodingPresets()) {
        if (empty && p.settings.empty()) return p.name;
        if (!empty && encoding == p.settings) return p.name;
    }
    // A project's array may spell a named one with every key written (a saved model's toJson()).
    if (!empty && encoding.is_array()) try {
            const json written = networkEncoding(encoding, kEncodingCheckInputs).toJson();
            for (const EncodingPreset& p : encodingPresets())
                if (!p.settings.empty() && networkEncoding(p.settings, kEncodingCheckInputs).toJson() == written)
                    return p.name;
        } catch (const InputError&) {
        }
    return "";
}

InputEncoding networkEncoding(const nlohmann::json& encoding, int inputs, const DerivedInputs& derived) {
    if (encoding.is_null() || (encoding.is_array() && encoding.empty())) {
        InputEncoding identity;
        identity.inputs = inputs;
        identity.derived = derived;
        return identity;
    }
    try {
        return InputEncoding::fromJson(JsonReader(encoding, "settings", "/network/encoding"), inputs, derived);
    } catch (const InputError& e) {
        throw SettingError(kEncodingSetting, e.where() + ": " + e.detail() + " (records of " + std::to_string(inputs) +
                                                 " inputs)");
    } catch (const std::invalid_argument& e) {
        throw SettingError(kEncodingSetting, e.what());
    }
}

bool encodingHasParameters(const nlohmann::json& encoding) {
    return networkEncoding(encoding, kEncodingCheckInputs, kEncodingCheckDerived).numParams() > 0;
}

void checkEncodingTrainer(const nlohmann::json& encoding, const TrainerConfig& trainer) {
    if (trainer.type == TrainerType::Adam || !encodingHasParameters(encoding)) return;
    throw SettingError(kEncodingSetting, "the encoding " + networkEncoding(encoding, kEncodingCheckInputs, kEncodingCheckDerived).describe() +
                                             " has trainable parameters, which only the adam trainer trains (trainer.type is " +
                                             trainer.typeName() + "; Levenberg-Marquardt's J^T J over the table entries "
                                             "does not fit in memory)");
}

void checkEnsembleEncoding(const nlohmann::json& encoding, int ensemble) {
    if (ensemble <= 1 || !encodingHasParameters(encoding)) return;
    throw SettingError("network.ensemble",
                       ensembleEncodingRefusal(networkEncoding(encoding, kEncodingCheckInputs, kEncodingCheckDerived).describe(), ensemble));
}

EncodingSettingView viewEncodingSetting(const nlohmann::json& encoding, int inputs, const DerivedInputs& derived) {
    EncodingSettingView v;
    v.presetName = encodingPresetName(encoding);
    try {
        v.hasParameters = encodingHasParameters(encoding);  // as the trainer check sees the array
    } catch (const InputError&) {
    }
    try {
        v.encoding = networkEncoding(encoding, inputs, derived);
    } catch (const InputError& e) {
        v.fits = false;
        v.error = e.what();
        v.encoding = InputEncoding();
        v.encoding.inputs = inputs;
        v.encoding.derived = derived;
    }
    return v;
}

bool setNamedEncoding(nlohmann::json& encoding, const std::string& name) {
    const EncodingPreset* preset = findEncodingPreset(name);
    if (!preset || encoding == preset->settings) return false;
    encoding = preset->settings;
    return true;
}

}  // namespace rrf
