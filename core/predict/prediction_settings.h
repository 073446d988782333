#pragma once
/// Settings of CPU prediction (the project's "prediction" section), shared by the CLI and the GUI:
///
///     "prediction": {"direct": "exact", "direct_samples": 64, "seed": 1,
///                    "gather": {"min_exponent": 50, "lobe_samples": 64, "diffuse_samples": 64,
///                               "direct_samples": 16, "caustic_samples": 64}}
///
/// "direct": "exact" (the default) computes direct light per pixel (core/predict/exact_direct.h) and
/// uses the networks for indirect light only, as Ren et al. 2013; "network" takes the direct term from
/// the networks too (the seed report's variant). "gather" traces the indirect light of sharply glossy surfaces one bounce
/// further (core/predict/glossy_gather.h); "min_exponent": 0 turns the exponent rule off, and with no
/// "objects" named the gather.

#include <cstdint>
#include <string>
#include <vector>

namespace rrf {

/// Largest "direct_samples" (each value is 1 … this).
constexpr int kMaxDirectSamples = 65536;
/// Largest "lobe_samples" and "diffuse_samples" of the glossy gather.
constexpr int kMaxGatherSamples = 4096;

/// The project's "prediction" section.
struct PredictionSettings {
    enum class Direct { Network, Exact };
    Direct direct = Direct::Exact;    ///< "direct": "exact" | "network"
    /// "direct_samples": light samples per pixel and area light (their shadow rays are traced only
    /// where the shadow casters cannot settle them, core/predict/shadow_casters.h)
    int directSamples = 64;
    uint64_t seed = 1;                ///< "seed": keys the exact direct light's samples
    /// "gather": the glossy gather (core/predict/glossy_gather.h).
    struct Gather {
        /// Phong materials with an exponent at least this are gathered; 0: none.
        double minExponent = 50.0;
        int lobeSamples = 64;     ///< "lobe_samples": directions from the Phong lobe per pixel
        int diffuseSamples = 64;  ///< "diffuse_samples": cosine-hemisphere directions per pixel
        int directSamples = 16;   ///< "direct_samples": exact direct light samples at each secondary point
        /// "second_lobe_samples", "second_diffuse_samples": a secondary point on a gathered object
        /// (a mirror seen in a mirror) gathers once more with these; its own secondary points use
        /// their networks. 0 and 0: the first bounce's secondary points all use their networks.
        int secondLobeSamples = 8;
        int secondDiffuseSamples = 4;
        /// "caustic_samples": light samples per caster plane for the glossy light that the camera's
        /// gathered pixels receive diffusely by way of a glossy face (core/predict/glossy_caustics.h),
        /// instead of from their cosine rays; 0: the cosine rays carry it. Exact direct light only.
        int causticSamples = 64;
        /// "objects": names of objects gathered whatever their material (a diffuse receiver of
        /// caustics); the project checks them against the scene.
        std::vector<std::string> objects;
        /// Anything is gathered: the exponent rule or named objects, with directions to gather.
        bool on() const { return (minExponent > 0.0 || !objects.empty()) && lobeSamples + diffuseSamples > 0; }
        bool operator==(const Gather& o) const {
            return minExponent == o.minExponent && lobeSamples == o.lobeSamples && diffuseSamples == o.diffuseSamples &&
                   directSamples == o.directSamples && secondLobeSamples == o.secondLobeSamples &&
                   secondDiffuseSamples == o.secondDiffuseSamples && causticSamples == o.causticSamples &&
                   objects == o.objects;
        }
    } gather;

    bool operator==(const PredictionSettings& o) const {
        return direct == o.direct && directSamples == o.directSamples && seed == o.seed && gather == o.gather;
    }

    const char* directName() const { return direct == Direct::Exact ? "exact" : "network"; }
};

}  // namespace rrf
