#pragma once
/// Settings of CPU prediction (the project's "prediction" section), shared by the CLI and the GUI:
///
///     "prediction": {"direct": "exact", "direct_samples": 64, "seed": 1}
///
/// "direct": "exact" (the default) computes direct light per pixel (core/predict/exact_direct.h) and
/// uses the networks for indirect light only, as Ren et al. 2013; "network" takes the direct term from
/// the networks too (the seed report's variant).

#include <cstdint>

#include <nlohmann/json.hpp>

#include "core/util/json_reader.h"

namespace rrf {

/// Largest "direct_samples" (each value is 1 … this).
constexpr int kMaxDirectSamples = 65536;

/// The project's "prediction" section.
struct PredictionSettings {
    enum class Direct { Network, Exact };
    Direct direct = Direct::Exact;    ///< "direct": "exact" | "network"
    /// "direct_samples": light samples per pixel and area light (their shadow rays are traced only
    /// where the shadow casters cannot settle them, core/predict/shadow_casters.h)
    int directSamples = 64;
    uint64_t seed = 1;                ///< "seed": keys the exact direct light's samples

    /// Reads the section (missing keys keep their defaults). Throws InputError naming the reader's
    /// file and the JSON pointer for unknown keys or bad values.
    static PredictionSettings fromJson(const JsonReader& section);
    nlohmann::json toJson() const;
    const char* directName() const { return direct == Direct::Exact ? "exact" : "network"; }
};

}  // namespace rrf
