#include "core/nn/network_options.h"

#include <stdexcept>

namespace rrf {

const char* targetModeName(TargetMode m) {
    switch (m) {
        case TargetMode::Direct: return "direct";
        case TargetMode::Indirect: return "indirect";
        case TargetMode::Separate: return "separate";
        case TargetMode::Joint: return "joint";
        case TargetMode::Global:
        default: return "global";
    }
}

TargetMode parseTargetMode(const std::string& s) {
    for (TargetMode m : {TargetMode::Global, TargetMode::Direct, TargetMode::Indirect, TargetMode::Separate,
                         TargetMode::Joint})
        if (s == targetModeName(m)) return m;
    throw std::invalid_argument("unknown target mode '" + s +
                                "' (expected global, direct, indirect, separate or joint)");
}

}  // namespace rrf
