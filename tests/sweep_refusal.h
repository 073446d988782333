#pragma once
/// The setting a sweep's refusal names, for the sweep tests: runs the sweep and returns
/// SettingError::setting() of what it threw, or "" when it ran or threw something else.

#include <string>

#include "core/pipeline/sweep.h"
#include "core/util/error.h"

namespace rrf::test {

inline std::string settingNamedBy(const Scene& scene, const SweepOptions& o) {
    try {
        runSweep(scene, o);
    } catch (const SettingError& e) {
        return e.setting();
    } catch (...) {
    }
    return "";
}

}  // namespace rrf::test
