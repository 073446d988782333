// Staged files (core/util/staged_files.h): a set's members are written plainly and flushed together
// just before the swap. A member whose flush fails (an I/O error, a full disk or quota that shows
// only at fsync) must stop the swap: the old set stays, the error names that member, and no
// temporary directory is left behind. The failure is injected through the flush seam.
#include <gtest/gtest.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "core/nn/model_set.h"
#include "core/util/atomic_file.h"
#include "core/nn/object_training.h"
#include "core/util/directory_replace.h"
#include "core/util/error.h"
#include "core/util/staged_files.h"
#include "tests/model_builders.h"
#include "tests/test_dirs.h"

namespace test_staged_files {

using namespace rrf;
using namespace rrf::test;
namespace fs = std::filesystem;

namespace {

/// A scratch directory of this file's tests (tests/test_dirs.h).
struct TempDir : ScopedTempDir {
    TempDir() : ScopedTempDir("rrf_staged_files") {}
};

/// The member whose flush fails (its file name), and how many flushes were asked for.
std::string failing;
int flushes = 0;

int failingFlush(int fd, const char* path) {
    ++flushes;
    if (fs::path(path).filename() == failing) {
        errno = EIO;
        return -1;
    }
    return ::fsync(fd);
}

/// Installs failingFlush for the test's scope.
struct FailingFlush {
    explicit FailingFlush(const std::string& member) {
        failing = member;
        flushes = 0;
        setStagedFileFlushForTesting(&failingFlush);
    }
    ~FailingFlush() { setStagedFileFlushForTesting(nullptr); }
};

const std::vector<std::string> kLayout(kTinyModelInputs, "x");

/// Entries of `dir` other than the target's own name (the temporaries a failed write must remove).
std::vector<std::string> siblingsOf(const fs::path& target) {
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(target.parent_path()))
        if (e.path().filename() != target.filename()) names.push_back(e.path().filename().string());
    return names;
}

}  // namespace

TEST(StagedFiles, AMemberThatCannotBeFlushedStopsTheSwapAndIsNamed) {
    TempDir tmp;
    const fs::path dir = tmp.path / "models";
    const std::vector<ObjectModel> old = tinyModelSet(1, 3);
    saveModelSet(dir.string(), old, 0x1234, kLayout);
    const std::string oldIndex = readFile((dir / "models.json").string());

    const std::string member = modelFileName(1, "global");
    std::string message;
    {
        FailingFlush flush(member);
        try {
            saveModelSet(dir.string(), tinyModelSet(2, 3), 0x1234, kLayout);
            ADD_FAILURE() << "saving succeeded although " << member << " could not be flushed";
        } catch (const OutputError& e) {
            message = e.what();
        }
        EXPECT_GE(flushes, 4) << "every member (3 networks and the index) is flushed";
    }
    EXPECT_NE(message.find(member), std::string::npos) << "the error names the member: " << message;
    EXPECT_NE(message.find(std::strerror(EIO)), std::string::npos) << "and why: " << message;
    EXPECT_NE(message.find(dir.string()), std::string::npos) << "under the target's name, not the staging directory's: "
                                                             << message;
    // The old set is still the one in place, whole, and nothing of the new one is left beside it.
    EXPECT_EQ(readFile((dir / "models.json").string()), oldIndex);
    const ModelSet loaded = loadModelSet(dir.string(), 0x1234);
    ASSERT_EQ(loaded.objects.size(), old.size());
    EXPECT_EQ(loaded.find(1)->byTarget.at("global").leaves[0].params, old[1].model.leaves[0].params);
    EXPECT_TRUE(siblingsOf(dir).empty()) << "a temporary directory was left: " << siblingsOf(dir).front();

    // With the flush working again the same save goes through.
    saveModelSet(dir.string(), tinyModelSet(2, 3), 0x1234, kLayout);
    EXPECT_NE(readFile((dir / "models.json").string()), oldIndex);
}

TEST(StagedFiles, AFailedFlushOfANewSetCreatesNothing) {
    TempDir tmp;
    const fs::path dir = tmp.path / "fresh";
    {
        FailingFlush flush("a.bin");
        EXPECT_THROW(replaceDirectory(dir.string(), [](const std::string&) { return true; },
                                      [](const std::string& staging) {
                                          writeStagedFile((fs::path(staging) / "a.bin").string(), "abc");
                                          writeStagedFile((fs::path(staging) / "b.bin").string(), "def");
                                      }),
                     OutputError);
    }
    EXPECT_FALSE(fs::exists(dir));
    EXPECT_TRUE(fs::is_empty(tmp.path));
}

}  // namespace test_staged_files
