#include "core/nn/encoding_presets.h"

#include "core/nn/ensemble.h"
#include "core/util/error.h"

namespace rrf {

namespace {

/// instant-NGP's grid scaled to the radiance networks' data (about 10^4–10^5 records per object):
/// 8 levels from 4 to 4·1.5^7 ≈ 68 cells per axis, 2^12 entries of 2 features per level (65 536
/// parameters, 512 KiB as float64 per network), so a coarse level is dense and a fine one hashed.
EncodingSettings hashGridOverPosition() {
    HashGridSettings g;
    g.levels = 8;
    g.log2TableSize = 12;
    g.featuresPerLevel = 2;
    g.baseResolution = 4;
    g.growth = 1.5;
    return encodingComponent(g, {"position"});
}

/// B one-blob bins per input over `groups`.
EncodingSettings oneBlob(std::vector<std::string> groups) { return encodingComponent(OneBlobSettings{16}, std::move(groups)); }

}  // namespace

const std::vector<EncodingPreset>& encodingPresets() {
    static const std::vector<EncodingPreset> presets = {
        {"raw", "the normalised inputs themselves (Ren et al. 2013)", {}},
        {"frequency", "sin/cos of 2^k*pi*x, k < 4, over position and light (NeRF), the rest raw",
         {encodingComponent(FrequencySettings{4, true}, {"position", "light"})}},
        {"one_blob", "16 one-blob bins per input over position, view, light and normal (NRC), the rest raw",
         {oneBlob({"position", "view", "light", "normal"})}},
        {"hash_grid", "a trainable multiresolution hash grid over position (instant-NGP; adam only), the rest raw",
         {hashGridOverPosition()}},
        {"hash_grid_one_blob", "the hash grid over position, 16 one-blob bins over view, light and normal (adam only)",
         {hashGridOverPosition(), oneBlob({"view", "light", "normal"})}},
    };
    return presets;
}

const EncodingPreset* findEncodingPreset(const std::string& name) {
    for (const EncodingPreset& p : encodingPresets())
        if (name == p.name) return &p;
    return nullptr;
}

NetworkEncodingSettings encodingPresetSettings(const std::string& name, const std::string& setting) {
    if (const EncodingPreset* p = findEncodingPreset(name)) return p->settings;
    throw SettingError(setting, "unknown encoding '" + name + "' (expected one of " + encodingPresetNames(", ") + ")");
}

std::string encodingPresetNames(const char* separator) {
    std::string names;
    for (const EncodingPreset& p : encodingPresets()) names += (names.empty() ? "" : separator) + std::string(p.name);
    return names;
}

std::string encodingPresetName(const NetworkEncodingSettings& encoding) {
    // A project's array may spell a named one with every key written (a saved model's components).
    for (const EncodingPreset& p : encodingPresets())
        if (sameEncoding(encoding, p.settings)) return p.name;
    return "";
}

InputEncoding networkEncoding(const NetworkEncodingSettings& encoding, int inputs, const DerivedInputs& derived) {
    return buildInputEncoding(encoding, inputs, derived, [inputs](const std::string& at, const std::string& what) {
        throw SettingError(kEncodingSetting, "/network/encoding" + at + ": " + what + " (records of " +
                                                 std::to_string(inputs) + " inputs)");
    });
}

bool encodingHasParameters(const NetworkEncodingSettings& encoding) {
    return networkEncoding(encoding, kEncodingCheckInputs, kEncodingCheckDerived).numParams() > 0;
}

void checkEncodingTrainer(const NetworkEncodingSettings& encoding, const TrainerConfig& trainer) {
    if (trainer.type == TrainerType::Adam || !encodingHasParameters(encoding)) return;
    throw SettingError(kEncodingSetting, "the encoding " + networkEncoding(encoding, kEncodingCheckInputs, kEncodingCheckDerived).describe() +
                                             " has trainable parameters, which only the adam trainer trains (trainer.type is " +
                                             trainer.typeName() + "; Levenberg-Marquardt's J^T J over the table entries "
                                             "does not fit in memory)");
}

void checkEnsembleEncoding(const NetworkEncodingSettings& encoding, int ensemble) {
    if (ensemble <= 1 || !encodingHasParameters(encoding)) return;
    throw SettingError("network.ensemble",
                       ensembleEncodingRefusal(networkEncoding(encoding, kEncodingCheckInputs, kEncodingCheckDerived).describe(), ensemble));
}

EncodingSettingView viewEncodingSetting(const NetworkEncodingSettings& encoding, int inputs, const DerivedInputs& derived) {
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

bool setNamedEncoding(NetworkEncodingSettings& encoding, const std::string& name) {
    const EncodingPreset* preset = findEncodingPreset(name);
    if (!preset || encoding == preset->settings) return false;
    encoding = preset->settings;
    return true;
}

}  // namespace rrf
