#pragma once
/// Settings of CPU prediction (the project's "prediction" section), shared by the CLI and the GUI:
///
///     "prediction": {"direct": "network", "direct_samples": 64, "seed": 1}
///
/// "direct": "exact" computes direct light with shadow rays instead of the networks (see predictor.h).

#include <cstdint>

#include <nlohmann/json.hpp>

#include "core/util/json_reader.h"

namespace rrf {

/// Largest "direct_samples" (each value is 1 … this).
constexpr int kMaxDirectSamples = 65536;

/// The project's "prediction" section.
struct PredictionSettings {
    enum class Direct { Network, Exact };
    Direct direct = Direct::Network;  ///< "direct": "network" | "exact"
    int directSamples = 64;           ///< "direct_samples": NEE samples per pixel for exact direct light
    uint64_t seed = 1;                ///< "seed": keys the exact direct light's samples

    /// Reads the section (missing keys keep their defaults). Throws InputError naming the reader's
    /// file and the JSON pointer for unknown keys or bad values.
    static PredictionSettings fromJson(const JsonReader& section);
    nlohmann::json toJson() const;
    const char* directName() const { return direct == Direct::Exact ? "exact" : "network"; }
};

}  // namespace rrf
