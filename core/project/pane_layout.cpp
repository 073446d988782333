#include "core/project/pane_layout.h"

#include <algorithm>
#include <cmath>

namespace rrf {

float PaneLayout::clampFraction(float f, float fallback) {
    if (!std::isfinite(f)) return fallback;
    return std::clamp(f, kMinFraction, kMaxFraction);
}

nlohmann::json PaneLayout::toJson() const { return nlohmann::json{{"left", left}, {"bottom", bottom}}; }

PaneLayout PaneLayout::fromJson(const JsonReader& section, std::vector<std::string>& warnings) {
    PaneLayout l;
    if (!section.isObject()) {
        warnings.push_back(InputError(section.file(), section.pointer(),
                                      "expected an object, got " + JsonReader::describe(section.value()) +
                                          "; the default layout is used")
                               .what());
        return l;
    }
    auto read = [&](const char* key, float fallback) {
        try {
            return clampFraction(section.floatOr(key, fallback), fallback);
        } catch (const InputError& e) {
            warnings.push_back(std::string(e.what()) + "; the default is used");
            return fallback;
        }
    };
    l.left = read("left", kDefaultLeft);
    l.bottom = read("bottom", kDefaultBottom);
    return l;
}

}  // namespace rrf
