#pragma once
/// Layout of one training record: the network inputs
///   hit point (3), view direction (3), light position (3), normal (3), BRDF parameters (n)
/// followed by the targets direct RGB (3) and indirect RGB (3), then the targets' noise: the
/// variance of each target's Monte Carlo mean, direct RGB (3) and indirect RGB (3), in radiance²
/// (−1 when a record had fewer than two finite path samples, so no variance could be estimated).
/// n depends on the materials present:
/// Lambert-only scenes carry the albedo (3); scenes with Phong materials carry kd (3), ks (3) and
/// log10(1 + exponent) (1), the logarithm because exponents span 1 … 1e6. The names are written into
/// dataset and model files so readers never guess.

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace rrf {

struct RecordLayout {
    std::vector<std::string> inputs;   ///< input names, in order
    std::vector<std::string> targets;  ///< "direct_r", ..., "indirect_b"
    /// "direct_var_r", ..., "indirect_var_b": variance of each target's mean, in target order.
    std::vector<std::string> noise;
    bool phong = false;

    static RecordLayout forScene(const Scene& scene);
    /// The noise column names every generator since dataset version 2 writes.
    static const std::vector<std::string>& noiseNames();
    int inputCount() const { return int(inputs.size()); }
    int targetCount() const { return int(targets.size()); }
    int noiseCount() const { return int(noise.size()); }
    int floatsPerRecord() const { return inputCount() + targetCount() + noiseCount(); }
    /// Writes the BRDF parameters of `m` (inputCount() − 12 floats) to `out`.
    void brdfParameters(const Material& m, float* out) const;
    /// Writes all inputCount() inputs of a surface point `p` with geometric normal `ng` and material
    /// `m`, seen from direction `wo` (unit, towards the viewer), with the light centred at
    /// `lightPos`. The normal is flipped to the viewer's side. The data generator and the G-buffer
    /// both call this, so training and prediction inputs cannot drift apart.
    void writeInputs(const Vec3& p, const Vec3& wo, const Vec3& lightPos, const Vec3& ng, const Material& m,
                     float* out) const;
};

}  // namespace rrf
