#pragma once
/// The input encoding of a project's networks as a setting (docs/design.md §10a): the project's
/// "network": {"encoding": [...]} array (nn/encoding.h), read into NetworkEncodingSettings
/// (nn/encoding_settings.h), the named encodings that the CLI's
/// `--encoding NAME`, the sweeps' `encoding` kind and the Network panel offer, and the encoding each
/// network gets from the array for its own input count.
///
///   raw                the identity: Ren et al. 2013's normalised inputs
///   frequency          sin/cos of 2^k·π·x' (NeRF) over position and light, the rest raw
///   one_blob           one-blob bins (NRC) over every geometric input (position, view, light, normal)
///   hash_grid          a multiresolution hash grid (instant-NGP) over position, the rest raw
///   hash_grid_one_blob the hash grid over position and one-blob over view, light and normal (NRC's
///                      mix: a trainable grid where detail is spatial, fixed bins for directions)
///
/// A new named encoding is one more row of encodingPresets() (encoding_presets.cpp).

#include <string>
#include <vector>

#include "core/nn/encoding.h"
#include "core/nn/encoding_settings.h"
#include "core/nn/trainer_config.h"

namespace rrf {

/// The setting's name in errors and sweeps.
constexpr const char* kEncodingSetting = "network.encoding";

/// One named encoding.
struct EncodingPreset {
    const char* name;     ///< "raw", "frequency", …: the CLI's --encoding value and the panel's label
    const char* summary;  ///< one line for help texts and tooltips
    NetworkEncodingSettings settings;  ///< the "encoding" array it stands for (empty for raw)
};

/// Every named encoding, in the order menus list them.
const std::vector<EncodingPreset>& encodingPresets();
/// The named encoding called `name`, or null.
const EncodingPreset* findEncodingPreset(const std::string& name);
/// The setting of the named encoding `name`; SettingError naming `setting` for an unknown
/// name, listing the known ones.
NetworkEncodingSettings encodingPresetSettings(const std::string& name, const std::string& setting = kEncodingSetting);
/// The names joined by `separator` ("raw|frequency|…"), for help texts and error messages.
std::string encodingPresetNames(const char* separator = "|");
/// The name of the named encoding that `encoding` is (sameEncoding: however it is spelled), or ""
/// (a project's own encoding).
std::string encodingPresetName(const NetworkEncodingSettings& encoding);

/// The record inputs a settings check assumes (12 geometric inputs and the 3 diffuse BRDF
/// parameters every scene has): "encoding" arrays are checked against it when read.
constexpr int kEncodingCheckInputs = 15;
/// The derived inputs a check that knows no network assumes (all of them: whether a network derives
/// the group an array names is checked where its settings are known, networkSettingsFromJson).
constexpr DerivedInputs kEncodingCheckDerived{true};

/// The encoding of a network whose records have `inputs` raw inputs and which derives `derived`
/// (nn/derived_inputs.h), from the setting; the identity (with `inputs` and `derived`) for an
/// empty one. A setting that does not fit is a SettingError naming "network.encoding" and what is
/// wrong (e.g. a group this network's records lack, or "reflected" in a network that does not derive it).
InputEncoding networkEncoding(const NetworkEncodingSettings& encoding, int inputs, const DerivedInputs& derived = {});
/// Throws SettingError naming "network.encoding" when the array has trainable parameters (a hash
/// grid) and `trainer` is not Adam: Levenberg–Marquardt's JᵀJ over the table entries is out of reach.
void checkEncodingTrainer(const NetworkEncodingSettings& encoding, const TrainerConfig& trainer);
/// Throws SettingError naming "network.ensemble" when `ensemble` > 1 and the setting has trainable
/// parameters: an ensemble's members merge into one network only over one fixed input map (nn/ensemble.h).
void checkEnsembleEncoding(const NetworkEncodingSettings& encoding, int ensemble);
/// True when the setting's encoding has trainable parameters (for the panel's warning).
bool encodingHasParameters(const NetworkEncodingSettings& encoding);

/// What a front end shows of an "encoding" setting for records of `inputs` raw inputs (and the
/// network's `derived` inputs), derived from
/// the setting in one place so that views (the Network panel) never build encodings themselves.
struct EncodingSettingView {
    std::string presetName;      ///< the named encoding the setting is, or "" (a project's own array)
    bool fits = true;            ///< false: the setting does not fit these records (`error` says why)
    std::string error;           ///< networkEncoding's message when !fits
    InputEncoding encoding;      ///< the network's encoding when it fits (else the identity)
    bool hasParameters = false;  ///< trainable tables (encodingHasParameters; false if the setting is invalid)
};
EncodingSettingView viewEncodingSetting(const NetworkEncodingSettings& encoding, int inputs, const DerivedInputs& derived = {});

/// Sets `encoding` to the named encoding `name`; false when the name is unknown or it already is.
bool setNamedEncoding(NetworkEncodingSettings& encoding, const std::string& name);

}  // namespace rrf
