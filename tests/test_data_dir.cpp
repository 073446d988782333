#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/util/data_dir.h"

namespace test_data_dir {

using namespace rrf;
namespace fs = std::filesystem;

namespace {

/// Sets (or unsets, for nullptr) RRF_DATA_DIR for one test and restores the caller's value.
class DataDirVariable {
public:
    explicit DataDirVariable(const char* value) {
        if (const char* old = std::getenv(kDataDirVariable)) saved_ = old;
        if (value) ::setenv(kDataDirVariable, value, 1);
        else ::unsetenv(kDataDirVariable);
    }
    ~DataDirVariable() {
        if (saved_) ::setenv(kDataDirVariable, saved_->c_str(), 1);
        else ::unsetenv(kDataDirVariable);
    }

private:
    std::optional<std::string> saved_;
};

/// A fresh directory per test.
fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / "rrf_data_dir_tests" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/// A directory with shaders/ and projects/, the two things that make a data directory.
fs::path makeDataDir(const fs::path& dir) {
    fs::create_directories(dir / "shaders");
    fs::create_directories(dir / "projects");
    return dir;
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string findError(const std::vector<fs::path>& candidates) {
    try {
        findDataDir(candidates);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    ADD_FAILURE() << "findDataDir found a data directory";
    return {};
}

}  // namespace

TEST(DataDir, CandidatesAreTheBuildTreeThenTheInstalledTree) {
    const std::vector<fs::path> c = dataDirCandidates("/opt/rrf/bin", nullptr);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0], fs::path("/opt/rrf/bin/share/rrf-workbench"));
    EXPECT_EQ(c[1], fs::path("/opt/rrf/share/rrf-workbench"));
}

TEST(DataDir, OverrideIsTheOnlyCandidate) {
    EXPECT_EQ(dataDirCandidates("/opt/rrf/bin", "/data/rrf"), std::vector<fs::path>{"/data/rrf"});
    // An empty variable counts as unset.
    EXPECT_EQ(dataDirCandidates("/opt/rrf/bin", "").size(), 2u);
    EXPECT_TRUE(dataDirCandidates("", nullptr).empty());
}

TEST(DataDir, FindsTheFirstDirectoryHoldingShadersAndProjects) {
    const fs::path root = freshDir("first");
    fs::create_directories(root / "only-shaders" / "shaders");
    const fs::path a = makeDataDir(root / "a"), b = makeDataDir(root / "b");
    EXPECT_FALSE(isDataDir(root / "only-shaders"));
    EXPECT_TRUE(isDataDir(a));
    EXPECT_EQ(findDataDir({root / "missing", root / "only-shaders", a, b}), a);
    EXPECT_EQ(findDataDir({b, a}), b);
}

TEST(DataDir, MissingDataNamesEveryPlaceLookedIn) {
    const fs::path root = freshDir("missing");
    const std::string msg = findError({root / "one", root / "two"});
    EXPECT_NE(msg.find((root / "one").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find((root / "two").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("shaders/ and projects/"), std::string::npos) << msg;
    EXPECT_NE(msg.find(kDataDirVariable), std::string::npos) << msg;
}

TEST(DataDir, ExecutableDirIsThisProgramsDirectory) {
    const fs::path dir = executableDir();
    ASSERT_FALSE(dir.empty());
    EXPECT_TRUE(dir.is_absolute());
    EXPECT_TRUE(fs::exists(dir / "rrf_tests")) << dir;
}

TEST(DataDir, BuildTreeHoldsACopyOfTheSourceData) {
    const DataDirVariable unset(nullptr);
    const fs::path dir = dataDir();
    EXPECT_EQ(dir, executableDir() / "share" / "rrf-workbench");
    EXPECT_EQ(shaderDir(), dir / "shaders");
    // Refreshed at build time: the copy equals the source tree's file.
    for (const char* shader : {"gbuffer.vert", "gbuffer.frag", "fullscreen.vert", "predict.frag"})
        EXPECT_EQ(readFile(shaderDir() / shader), readFile(fs::path(RRF_SOURCE_DIR) / "shaders" / shader)) << shader;
    const fs::path cornell = bundledProject(kDefaultProject);
    EXPECT_EQ(cornell, dir / "projects" / "cornell-box" / "project.json");
    EXPECT_EQ(readFile(cornell), readFile(fs::path(RRF_SOURCE_DIR) / "projects" / "cornell-box" / "project.json"));
}

TEST(DataDir, VariableOverridesTheBuildTree) {
    const fs::path other = makeDataDir(freshDir("override") / "share");
    const DataDirVariable set(other.c_str());
    EXPECT_EQ(dataDir(), other);
    EXPECT_EQ(bundledProject("scene-x"), other / "projects" / "scene-x" / "project.json");
}

TEST(DataDir, WrongVariableIsReportedNotReplaced) {
    const fs::path wrong = freshDir("wrong") / "nothing-here";
    const DataDirVariable set(wrong.c_str());
    try {
        dataDir();
        FAIL() << "a wrong RRF_DATA_DIR fell back to another directory";
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(std::string(kDataDirVariable) + "=" + wrong.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find("shaders/ and projects/"), std::string::npos) << msg;
    }
}

}  // namespace test_data_dir
