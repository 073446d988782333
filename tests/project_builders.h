#pragma once
// Projects for tests: the bundled Cornell box's scene with chosen project sections, written to a
// file under the test's temporary directory and loaded as `rrf` loads a project.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/project/project.h"
#include "core/project/project_file.h"

namespace rrf::test {

/// The Cornell box project with `sections` added (e.g. {"network": {...}}), written as
/// `<temp dir>/<subdir>/<name>` and loaded with loadProjectOrScene.
inline Project cornellProjectWith(const std::string& subdir, const std::string& name, const nlohmann::json& sections) {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / subdir;
    std::filesystem::create_directories(dir);
    nlohmann::json doc = {{"rrf_project", 1},
                          {"scene", std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/scene.json"}};
    for (auto it = sections.begin(); it != sections.end(); ++it) doc[it.key()] = it.value();
    const std::string path = (dir / name).string();
    std::ofstream(path) << doc.dump(2);
    return loadProjectOrScene(path);
}

}  // namespace rrf::test
