#pragma once
/// The effects of a scene (scene/effects.h) as the "effects" object of render.json and of a
/// dataset header.

#include <nlohmann/json.hpp>

#include "core/scene/effects.h"

namespace rrf {

/// Every flag, the largest albedo and Phong exponent, and "description" (Effects::describe()).
nlohmann::json toJson(const Effects& e);

}  // namespace rrf
