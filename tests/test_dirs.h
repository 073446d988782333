#pragma once
/// A fresh directory per test for tests that write real files: CTest runs each test in its own
/// process, possibly in parallel, so the directory is named after the test and the process.

#include <filesystem>
#include <string>
#include <system_error>

#include <gtest/gtest.h>
#include <unistd.h>

namespace rrf::test {

/// `<temp>/<prefix>_<test name>_<pid>`, emptied and created.
inline std::filesystem::path freshTestDir(const std::string& prefix) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / (prefix + "_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// `<temp>/<prefix>_<pid>_<n>` (n counts the directories the process made, so a test may hold
/// several), emptied and created, and removed with its contents when it goes out of scope.
struct ScopedTempDir {
    std::filesystem::path path;
    explicit ScopedTempDir(const std::string& prefix) {
        static int counter = 0;
        path = std::filesystem::temp_directory_path() /
               (prefix + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~ScopedTempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
    ScopedTempDir(const ScopedTempDir&) = delete;
    ScopedTempDir& operator=(const ScopedTempDir&) = delete;
};

/// True if `part` occurs in `s` (messages are checked for the parts that matter).
inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace rrf::test
