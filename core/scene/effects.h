#pragma once
/// The light-transport effects a scene calls for, derived from its materials, lights and geometry.
/// The path tracer runs only the code paths listed here (no Phong evaluation in a Lambert scene, no
/// bounce rays when no surface can light another), and the list is printed and stored with every
/// output so a user sees what was simulated (as JSON by scene/effects_json.h).

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace rrf {

/// The Phong exponent from which a lobe counts as caustic-forming: its width (about √(2/n) rad) is
/// then under ~0.3 rad, a small part of a diffuse bounce's hemisphere, so a BRDF-sampled path
/// rarely passes through it towards the light; broader lobes are found by the path tracer's MIS.
constexpr double kCausticExponent = 20.0;

struct Effects {
    bool diffuse = false;            ///< some material has kd > 0
    bool glossy = false;             ///< some Phong material has ks > 0
    bool rectLights = false;         ///< rect lights (sampled by NEE, visible to rays)
    bool triangleLights = false;     ///< triangle emitters, e.g. an OBJ's mesh lamps (NEE picks one by area)
    bool pointLights = false;        ///< point lights (NEE only: no ray can hit them)
    bool reflectiveEmitters = false; ///< an emitter surface that also reflects (furnace scenes)
    bool indirect = false;           ///< light can bounce between surfaces (≥ 2 reflecting surfaces, or a concave one)
    /// Glossy lobes narrow enough to focus an emitter's light onto diffuse surfaces, where the path
    /// tracer finds it only by rare BRDF samples: a Phong material of exponent >= kCausticExponent,
    /// a diffuse material and indirect light. Estimator "auto" renders such scenes bidirectionally.
    bool caustics = false;
    float maxAlbedo = 0.f;           ///< largest kd+ks component: how long Russian roulette keeps paths
    double maxPhongExponent = 0.0;

    static Effects derive(const Scene& scene);
    /// One human-readable line per effect, e.g. "glossy reflection (Phong, exponent up to 100)".
    std::vector<std::string> describe() const;
};

}  // namespace rrf
