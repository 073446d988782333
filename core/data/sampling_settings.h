#pragma once
/// Settings of the training-data generator (the project's "sampling" section), shared by the CLI and
/// the GUI so both generate the same data from the same project.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "core/render/render_settings.h"

namespace rrf {

struct SamplingSettings {
    int nx = 15, ny = 15, nz = 15;  ///< jitter grid over the scene bounds
    int directions = 1200;          ///< random directions per viewpoint (N_dir)
    int spp = 64;                   ///< paths per record for the direct/indirect targets
    uint64_t seed = 1;
    bool fixedLight = false;        ///< true: every record uses the scene's light position
    Estimator estimator = Estimator::NEE;
    int maxDepth = 64;

    int cellCount() const { return nx * ny * nz; }
    /// Reads the "sampling" section; missing keys keep their defaults. Throws InputError naming
    /// `file` and the JSON path for unknown keys, wrong types or out-of-range values.
    static SamplingSettings fromJson(const nlohmann::json& j, const std::string& file,
                                     const std::string& path = "/sampling");
    nlohmann::json toJson() const;
};

}  // namespace rrf
