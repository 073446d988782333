#include "core/data/sampling_settings.h"

namespace rrf {

const std::vector<std::string>& SamplingSettings::keys() {
    static const std::vector<std::string> k = {"grid",  "directions", "spp",      "max_spp",
                                               "noise_target", "seed", "light", "estimator", "max_depth"};
    return k;
}

}  // namespace rrf
