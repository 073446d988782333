#pragma once
/// Flags that set fields of the typed settings (sampling, network and trainer, prediction, render).
///
/// The settings come from the project named on the same command line, so they exist only after
/// parsing: CLI11 converts and checks each flag's value into the field's type while it parses, and
/// the command writes the flags that were given over the project's values with applyTo(). Each
/// setting has the spelling it has in the project file, written without brackets:
///
///     project "grid": [15, 15, 15]   --grid 15,15,15   (exactly 3 integers)
///     project "hidden": [20, 10]     --hidden 20,10    (a list of integers)
///
/// and a sweep's values are spelled the same way, one setting per value (`--values 5 10,5 20,10`).

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/data/sampling_settings.h"
#include "core/nn/object_training.h"
#include "core/predict/prediction_settings.h"
#include "core/pipeline/presets.h"
#include "core/util/vec3.h"

namespace rrf {
struct Project;
}

namespace rrf::cli {

/// Adds `flag`, converted and checked by CLI11 as a T (an int, a string, or a std::vector of numbers
/// with a delimiter); `check`, if given, judges the whole value while parsing (e.g. its length) and
/// returns why it is wrong, or "". `store` receives the value.
template <class T>
CLI::Option* addCheckedOption(CLI::App* cmd, const std::string& flag, const std::string& help,
                              std::function<void(const T&)> store, std::function<std::string(const T&)> check = {}) {
    return cmd->add_option_function<T>(
        flag,
        [store, check, flag](const T& v) {
            if (check)
                if (const std::string why = check(v); !why.empty()) throw CLI::ValidationError(flag, why);
            store(v);
        },
        help);
}

/// A check for addCheckedOption: exactly `n` numbers, written as `spelling` (e.g. "nx,ny,nz").
template <class Number>
std::function<std::string(const std::vector<Number>&)> exactly(size_t n, const std::string& spelling) {
    return [n, spelling](const std::vector<Number>& v) -> std::string {
        if (v.size() == n) return "";
        return "expected exactly " + std::to_string(n) + " numbers " + spelling + ", got " + std::to_string(v.size());
    };
}

/// Flags that override fields of one settings struct.
template <class Settings>
class SettingFlags {
public:
    /// Adds `flag` as addCheckedOption does; when given, `set(settings, value)` writes it.
    template <class T>
    CLI::Option* add(CLI::App* cmd, const std::string& flag, const std::string& help,
                     std::function<void(Settings&, const T&)> set, std::function<std::string(const T&)> check = {}) {
        auto value = std::make_shared<std::optional<T>>();
        setters_.push_back([value, set](Settings& s) {
            if (*value) set(s, **value);
        });
        return addCheckedOption<T>(cmd, flag, help, [value](const T& v) { *value = v; }, check);
    }

    /// Writes the flags that were given over `settings`, in the order they were added (so --trainer
    /// switches the trainer before --epochs sets its limit).
    void applyTo(Settings& settings) const {
        for (const auto& set : setters_) set(settings);
    }

    /// `settings` with the given flags written over it.
    Settings applied(Settings settings) const {
        applyTo(settings);
        return settings;
    }

private:
    std::vector<std::function<void(Settings&)>> setters_;
};

/// A finite number (each element of a list): CLI11 converts "nan" and "inf" to floating values that
/// its Range and PositiveNumber checks let through, since every comparison with NaN is false.
/// Check it before a range.
const CLI::Validator& finiteNumber();

/// Positive and non-negative integers, with a readable message (CLI11's PositiveNumber prints the
/// largest double as its range).
const CLI::Validator& positive();
const CLI::Validator& nonNegative();

/// --grid NX,NY,NZ, --dirs N and the paths per record under `sppFlag` (--spp for `rrf generate`,
/// --data-spp where --spp is the reference's).
void addSamplingFlags(CLI::App* cmd, SettingFlags<SamplingSettings>& flags, const std::string& sppFlag);
/// --estimator nee|naive|bdpt|auto into `target` (empty: the project's); `what` names what it renders.
CLI::Option* addEstimatorOption(CLI::App* cmd, std::string& target, const std::string& what);
/// The project's render estimator replaced by `flag` when given (a value addEstimatorOption checked).
void applyEstimatorFlag(const std::string& flag, Estimator& estimator);

/// --hidden N,N,..., --ensemble K, --encoding NAME (nn/encoding_presets.h), --trainer lm|adam and --epochs N.
void addNetworkFlags(CLI::App* cmd, SettingFlags<ObjectTrainingOptions>& flags);

/// `flag` x,y,z: exactly three finite numbers, stored in `target` when given.
CLI::Option* addVec3Option(CLI::App* cmd, const std::string& flag, std::optional<Vec3>& target, const std::string& help);

/// The options of every command that predicts with networks (evaluate, predict, sweep, pipeline).
struct PredictionArgs {
    std::string input, out;
    int threads = 0, width = -1, height = -1;
    SettingFlags<PredictionSettings> prediction;  ///< --direct, --direct-samples
};

/// input, --out, --threads, --width, --height, --direct and --direct-samples.
void addPredictionOptions(CLI::App* cmd, PredictionArgs& a);

/// The flags of the commands that generate data and train on it in one run (sweep, pipeline).
struct ExperimentFlags {
    SettingFlags<SamplingSettings> sampling;     ///< --grid, --dirs, --data-spp
    SettingFlags<ObjectTrainingOptions> network;  ///< --hidden, --ensemble, --encoding, --reflected, --trainer, --epochs
};

void addExperimentFlags(CLI::App* cmd, ExperimentFlags& flags);

/// --noise and --spp-cap, the noise target of references from the project's store (one spelling and
/// range for every command): `noise` and `sppCap` stay ≤ 0 when not given (noiseTargetFor then keeps
/// the project's). `which` names the references in the help ("the held-out references"), `capDefault`
/// the cap's default as the command applies it; `relaxedByError`: the command measures an error and
/// relaxes the target to a quarter of it. When `fixedSpp` is given, both exclude it.
void addNoiseTargetFlags(CLI::App* cmd, double& noise, int& sppCap, const std::string& which,
                         const std::string& capDefault, bool relaxedByError, CLI::Option* fixedSpp = nullptr);

/// Data and network settings of the pipeline and of sweeps: the project's sections (its defaults
/// where absent), changed by `preset` when given (core/pipeline/presets.h), then the flags.
void experimentSettings(const Project& p, const ExperimentFlags& flags, const PipelinePreset* preset, SamplingSettings& s,
                        ObjectTrainingOptions& t);
/// The "quick" row of the preset table (`--quick`, the sweeps' sizes).
const PipelinePreset& quickPreset();

/// One line: grid, directions, spp per record, network, targets, trainer and epochs.
std::string describeExperiment(const SamplingSettings& s, const ObjectTrainingOptions& t);

}  // namespace rrf::cli
