// The bundled project is not edited in place (issue 14 item 5): a first start copies it into the
// per-user workspace ($XDG_DATA_HOME/rrf-workbench/projects/<name>) and later starts reuse that
// copy, keeping the user's work in it.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "app/gui/user_workspace.h"

namespace rrf::test::test_user_workspace {

namespace fs = std::filesystem;

namespace {
std::string readText(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Sets an environment variable for the scope of a test.
class EnvVar {
public:
    EnvVar(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old, had_ = true;
        ::setenv(name, value.c_str(), 1);
    }
    ~EnvVar() {
        if (had_) ::setenv(name_, old_.c_str(), 1);
        else ::unsetenv(name_);
    }

private:
    const char* name_;
    std::string old_;
    bool had_ = false;
};
}  // namespace

TEST(UserWorkspace, FirstStartCopiesTheBundledProjectAndLaterStartsKeepTheCopy) {
    const fs::path root = fs::temp_directory_path() / ("rrf_gui_workspace_" + std::to_string(::getpid()));
    fs::remove_all(root);
    const fs::path bundled = root / "share/projects/cornell-box";
    fs::create_directories(bundled / "meshes");
    std::ofstream(bundled / "project.json") << "{\"project\": 1}";
    std::ofstream(bundled / "meshes/box.obj") << "v 0 0 0";
    const EnvVar data("XDG_DATA_HOME", (root / "data").string());

    EXPECT_EQ(userDataDir(), (root / "data" / "rrf-workbench").string());
    bool created = false;
    const std::string project = userWorkspaceProject((bundled / "project.json").string(), created);
    EXPECT_TRUE(created);
    const fs::path copy = root / "data/rrf-workbench/projects/cornell-box";
    EXPECT_EQ(fs::path(project), copy / "project.json");
    EXPECT_EQ(readText(copy / "project.json"), "{\"project\": 1}");
    EXPECT_EQ(readText(copy / "meshes/box.obj"), "v 0 0 0") << "the whole project directory is copied";
    EXPECT_FALSE(fs::exists(root / "data/rrf-workbench/projects/cornell-box.partial"));

    // The user works in the copy; the next start opens it as it is.
    std::ofstream(copy / "project.json") << "{\"project\": 2}";
    EXPECT_EQ(userWorkspaceProject((bundled / "project.json").string(), created), project);
    EXPECT_FALSE(created);
    EXPECT_EQ(readText(copy / "project.json"), "{\"project\": 2}");
    EXPECT_EQ(readText(bundled / "project.json"), "{\"project\": 1}") << "the bundled project is never written";
    fs::remove_all(root);
}

TEST(UserWorkspace, WithoutXdgDataHomeTheWorkspaceIsUnderHome) {
    const EnvVar data("XDG_DATA_HOME", "");
    const EnvVar home("HOME", "/home/someone");
    EXPECT_EQ(userDataDir(), "/home/someone/.local/share/rrf-workbench");
}

}  // namespace rrf::test::test_user_workspace
