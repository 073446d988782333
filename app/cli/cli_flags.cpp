#include "app/cli/cli_flags.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/nn/mlp_kernel.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/network_settings.h"
#include "core/nn/trainers/registry.h"
#include "core/pipeline/presets.h"
#include "core/project/project.h"

namespace rrf::cli {

namespace {
/// Each element of a ',' list must be a finite number ("nan" and "inf" convert to a float).
const CLI::Validator kFinite(
    [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v)) return "expected a finite number, got '" + text + "'";
        return {};
    },
    "");

CLI::Validator atLeast(long long min, const char* what, const char* name) {
    return CLI::Validator(
        [min, what](std::string& text) -> std::string {
            long long v = 0;
            if (CLI::detail::lexical_cast(text, v) && v >= min) return {};
            return std::string("expected ") + what + ", got '" + text + "'";
        },
        name);
}
}  // namespace

const CLI::Validator& finiteNumber() { return kFinite; }

const CLI::Validator& positive() {
    static const CLI::Validator v = atLeast(1, "a positive integer", "POSITIVE");
    return v;
}

const CLI::Validator& nonNegative() {
    static const CLI::Validator v = atLeast(0, "a non-negative integer", "NONNEGATIVE");
    return v;
}

void addSamplingFlags(CLI::App* cmd, SettingFlags<SamplingSettings>& flags, const std::string& sppFlag) {
    // One word per flag (allow_extra_args(false)): "--grid 4,4" must not take the next flag as its third number.
    flags
        .add<std::vector<int>>(
            cmd, "--grid", "jitter grid: exactly 3 integers, e.g. 15,15,15 (default: the project's)",
            [](SamplingSettings& s, const std::vector<int>& g) {
                s.nx = g[0];
                s.ny = g[1];
                s.nz = g[2];
            },
            exactly<int>(3, "nx,ny,nz"))
        ->delimiter(',')
        ->allow_extra_args(false)
        ->check(CLI::Range(1, kMaxGridCells))
        ->type_name("NX,NY,NZ");
    flags.add<int>(cmd, "--dirs", "directions per viewpoint", [](SamplingSettings& s, const int& n) { s.directions = n; })
        ->check(CLI::Range(1, kMaxDirections));
    flags.add<int>(cmd, sppFlag, "paths per record", [](SamplingSettings& s, const int& n) { s.spp = n; })
        ->check(CLI::Range(1, kMaxSamplesPerRecord));
    flags.add<std::string>(cmd, "--record-estimator", "estimator of the training records (nee, naive, bdpt, auto)",
                           [](SamplingSettings& s, const std::string& m) { s.estimator = *parseEstimator(m); })
        ->check(CLI::IsMember(estimatorChoices()));
}

CLI::Option* addEstimatorOption(CLI::App* cmd, std::string& target, const std::string& what) {
    return cmd
        ->add_option("--estimator", target,
                     "estimator of " + what + " (auto: bdpt where glossy lobes form caustics, else nee; default: the project's)")
        ->check(CLI::IsMember(estimatorChoices()));
}

void applyEstimatorFlag(const std::string& flag, Estimator& estimator) {
    if (const std::optional<Estimator> e = parseEstimator(flag)) estimator = *e;
}

void addNetworkFlags(CLI::App* cmd, SettingFlags<ObjectTrainingOptions>& flags) {
    flags.add<std::vector<int>>(cmd, "--hidden", "hidden layer sizes: a list of integers, e.g. 20,10",
                                [](ObjectTrainingOptions& t, const std::vector<int>& h) {
                                    // Every network: per-object "hidden" entries give way (object_network_overrides.h).
                                    t.hidden = h;
                                    dropHiddenOverrides(t.perObject);
                                })
        ->delimiter(',')
        ->allow_extra_args(false)
        ->check(CLI::Range(1, kMaxHiddenSize))
        ->type_name("N[,N...]");
    flags.add<int>(cmd, "--ensemble", "networks averaged per leaf (network.ensemble; nn/ensemble.h)",
                   [](ObjectTrainingOptions& t, const int& n) { t.ensemble = n; })
        ->check(CLI::Range(1, kMaxEnsembleMembers));
    std::vector<std::string> encodings;
    for (const EncodingPreset& e : encodingPresets()) encodings.push_back(e.name);
    flags.add<std::string>(cmd, "--encoding", "input encoding of every network, by name (network.encoding; default: the project's)",
                           [](ObjectTrainingOptions& t, const std::string& name) {
                               t.encoding = encodingPresetSettings(name);
                               dropEncodingOverrides(t.perObject);
                           })
        ->check(CLI::IsMember(encodings));
    flags.add<std::string>(cmd, "--reflected",
                           "the view direction reflected about the normal as an input of every network, on or off "
                           "(network.inputs.reflected; default: the project's)",
                           [](ObjectTrainingOptions& t, const std::string& v) {
                               t.inputs.reflected = v == "on";
                               dropInputsOverrides(t.perObject);
                           })
        ->check(CLI::IsMember({"on", "off"}));
    flags.add<std::string>(cmd, "--trainer", "trainer",
                           [](ObjectTrainingOptions& t, const std::string& type) { t.trainer = t.trainer.withType(type); })
        ->check(CLI::IsMember(trainerShortNames()));
    flags.add<int>(cmd, "--epochs", "maximum epochs", [](ObjectTrainingOptions& t, const int& n) {
             for (TrainerCommon* c : t.trainer.everyTrainer()) c->maxEpochs = n;
         })->check(positive());
}

CLI::Option* addVec3Option(CLI::App* cmd, const std::string& flag, std::optional<Vec3>& target, const std::string& help) {
    return addCheckedOption<std::vector<float>>(
               cmd, flag, help, [&target](const std::vector<float>& v) { target = Vec3(v[0], v[1], v[2]); },
               exactly<float>(3, "x,y,z"))
        ->delimiter(',')
        ->allow_extra_args(false)
        ->check(kFinite)
        ->type_name("X,Y,Z");
}

void addPredictionOptions(CLI::App* cmd, PredictionArgs& a) {
    cmd->add_option("input", a.input, "project or scene JSON file")->required();
    cmd->add_option("--out", a.out, "output directory")->required();
    cmd->add_option("--threads", a.threads, "worker threads (0 = all cores)")->check(nonNegative());
    cmd->add_option("--width", a.width, "image width (default: the project's)")->check(CLI::Range(1, kMaxImageSide));
    cmd->add_option("--height", a.height, "image height (default: the project's)")->check(CLI::Range(1, kMaxImageSide));
    a.prediction
        .add<std::string>(cmd, "--direct", "direct light from the networks or exact shadow rays (default: the project's)",
                          [](PredictionSettings& s, const std::string& d) {
                              s.direct = d == "exact" ? PredictionSettings::Direct::Exact : PredictionSettings::Direct::Network;
                          })
        ->check(CLI::IsMember({"network", "exact"}));
    a.prediction
        .add<int>(cmd, "--direct-samples", "exact direct light's samples (shadow rays) per pixel and light (default: the project's)",
                  [](PredictionSettings& s, const int& n) { s.directSamples = n; })
        ->check(CLI::Range(1, kMaxDirectSamples));
    a.prediction
        .add<std::string>(cmd, "--gather",
                          "glossy gather: sharply glossy objects' indirect light traced one bounce further, on (the "
                          "project's threshold, or Phong exponent 50 if it has none) or off (none gathered, named "
                          "objects neither; default: the project's)",
                          [](PredictionSettings& s, const std::string& v) {
                              const double on = s.gather.minExponent > 0.0 ? s.gather.minExponent
                                                                           : PredictionSettings().gather.minExponent;
                              s.gather.minExponent = v == "on" ? on : 0.0;
                              if (v == "off") s.gather.objects.clear();
                          })
        ->check(CLI::IsMember({"on", "off"}));
}

void addExperimentFlags(CLI::App* cmd, ExperimentFlags& flags) {
    addSamplingFlags(cmd, flags.sampling, "--data-spp");
    addNetworkFlags(cmd, flags.network);
}

void experimentSettings(const Project& p, const ExperimentFlags& flags, const PipelinePreset* preset, SamplingSettings& s,
                        ObjectTrainingOptions& t) {
    s = preset ? presetSampling(p, *preset) : p.samplingOrDefault();
    t = preset ? presetNetwork(p, *preset) : p.trainingOptions();
    flags.sampling.applyTo(s);
    flags.network.applyTo(t);
}

const PipelinePreset& quickPreset() {
    static const PipelinePreset& quick = *findPreset("quick");
    return quick;
}

void addNoiseTargetFlags(CLI::App* cmd, double& noise, int& sppCap, const std::string& which,
                         const std::string& capDefault, bool relaxedByError, CLI::Option* fixedSpp) {
    CLI::Option* n = cmd->add_option("--noise", noise,
                                     "relative RMSE noise (global term) " + which + " must reach (default: the project's "
                                     "\"reference\" section, 0.01" +
                                         std::string(relaxedByError ? "; or a quarter of the measured error when that is larger)" : ")"))
                         ->check(kFinite)
                         ->check(CLI::Range(1e-6, 10.0));
    CLI::Option* c = cmd->add_option("--spp-cap", sppCap, "most samples per pixel of " + which + " (default: " + capDefault + ")")
                         ->check(CLI::Range(2, 1 << 24));
    if (fixedSpp) {
        n->excludes(fixedSpp);
        c->excludes(fixedSpp);
    }
}

std::string describeExperiment(const SamplingSettings& s, const ObjectTrainingOptions& t) {
    char buf[384];
    const std::string encoding = encodingPresetName(t.encoding);
    std::snprintf(buf, sizeof buf, "grid %dx%dx%d, %d directions, %d spp per record; network %s%s, encoding %s%s%s, targets %s, %s, %d epochs, kernel %s",
                  s.nx, s.ny, s.nz, s.directions, s.spp, hiddenSizesText(t.hidden).c_str(),
                  t.ensemble > 1 ? (" x" + std::to_string(t.ensemble)).c_str() : "",
                  encoding.empty() ? "(the project's)" : encoding.c_str(), t.inputs.reflected ? " +reflected" : "",
                  t.perObject.empty() ? "" : " (per-object entries)", targetModeName(t.targets), t.trainer.typeName(),
                  t.trainer.maxEpochs(), mlpKernelDescription(mlpKernel()).c_str());
    return buf;
}

}  // namespace rrf::cli
