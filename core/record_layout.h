#pragma once
/// Layout of one training record: the network inputs
///   hit point (3), view direction (3), light position (3), normal (3), BRDF parameters (n)
/// followed by the targets direct RGB (3) and indirect RGB (3). n depends on the materials present:
/// Lambert-only scenes carry the albedo (3); scenes with Phong materials carry kd (3), ks (3) and
/// log10(1 + exponent) (1), the logarithm because exponents span 1 … 1e6. The names are written into
/// dataset and model files so readers never guess.

#include <string>
#include <vector>

#include "core/scene.h"

namespace rrf {

struct RecordLayout {
    std::vector<std::string> inputs;   ///< input names, in order
    std::vector<std::string> targets;  ///< "direct_r", ..., "indirect_b"
    bool phong = false;

    static RecordLayout forScene(const Scene& scene);
    int inputCount() const { return int(inputs.size()); }
    int targetCount() const { return int(targets.size()); }
    int floatsPerRecord() const { return inputCount() + targetCount(); }
    /// Writes the BRDF parameters of `m` (inputCount() − 12 floats) to `out`.
    void brdfParameters(const Material& m, float* out) const;
};

}  // namespace rrf
