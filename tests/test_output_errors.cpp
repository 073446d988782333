// Errors of the atomic-output machinery name the output the user asked for and what is left there,
// never the temporary file or directory the write went through (issue 31: a full disk during
// `rrf render` named `/…/.render.32701.0.tmp/global.exr`). Single files (AtomicFile), sets
// replaced as a whole (replaceDirectory, and through it model sets and reference entries), an image
// refused by its encoder inside a set, on a full disk simulated by RLIMIT_FSIZE
// (tests/file_size_limit.h); and the directory fsync after a rename.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include <unistd.h>

#include "core/eval/reference_store.h"
#include "core/render/render_settings.h"
#include "core/util/atomic_file.h"
#include "core/util/directory_replace.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "scene_builders.h"
#include "tests/file_size_limit.h"
#include "tests/model_builders.h"
#include "tests/test_dirs.h"

namespace test_output_errors {

using namespace rrf;
using namespace rrf::test;
namespace fs = std::filesystem;

namespace {

fs::path testDir() { return freshTestDir("rrf_output_errors"); }

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Entries of `dir` that a write leaves only while it runs: temporaries (*.tmp, .<name>.…).
int leftovers(const fs::path& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        n += name[0] == '.' || e.path().extension() == ".tmp";
    }
    return n;
}

const std::string kBig(64 * 1024, 'x');  // beyond the 8 KiB "disk" of the tests

}  // namespace

TEST(OutputErrors, FullDiskDuringAFileWriteNamesTheFileAndWhatWasKept) {
    const fs::path dir = testDir();
    const std::string old = (dir / "old.bin").string(), fresh = (dir / "fresh.bin").string();
    writeFileAtomically(old, "previous");
    const FileSizeLimit limit(8192);
    ASSERT_TRUE(limit.active());
    for (const auto& [path, kept] : {std::pair{old, "the previous file is kept"}, std::pair{fresh, "no file was created"}}) {
        try {
            writeFileAtomically(path, kBig);
            ADD_FAILURE() << "64 KiB written under an 8 KiB limit";
        } catch (const OutputError& e) {
            EXPECT_EQ(std::string(e.what()), path + ": write failed: File too large; " + kept);
            EXPECT_EQ(e.path(), path);
        }
    }
    EXPECT_EQ(readText(old), "previous");
    EXPECT_FALSE(fs::exists(fresh));
    EXPECT_EQ(leftovers(dir), 0);
    fs::remove_all(dir);
}

TEST(OutputErrors, FullDiskDuringASetWriteNamesTheSetsFileNotTheTemporaryDirectory) {
    const fs::path dir = testDir();
    const std::string set = (dir / "set").string(), fresh = (dir / "fresh").string();
    replaceDirectory(set, [](const std::string&) { return true; },
                     [](const std::string& staging) { writeFileAtomically(staging + "/a.txt", "old set"); });
    auto fill = [](const std::string& staging) {
        writeFileAtomically(staging + "/a.txt", "new set");
        writeFileAtomically(staging + "/big.bin", kBig);
    };
    const FileSizeLimit limit(8192);
    ASSERT_TRUE(limit.active());
    const struct {
        std::string target, kept;
    } cases[] = {{set, "the previous contents of '" + set + "' are kept"}, {fresh + "/", "'" + fresh + "' was not created"}};
    for (const auto& c : cases) {
        try {
            replaceDirectory(c.target, [](const std::string&) { return true; }, fill);
            ADD_FAILURE() << "a 64 KiB member written under an 8 KiB limit";
        } catch (const OutputError& e) {
            // The user's spelling of the target (its trailing '/' dropped), the member, what failed, what is kept.
            const std::string shown = c.target.back() == '/' ? c.target.substr(0, c.target.size() - 1) : c.target;
            EXPECT_EQ(std::string(e.what()), shown + "/big.bin: write failed: File too large; " + c.kept);
            EXPECT_FALSE(contains(e.what(), ".tmp")) << e.what();
        }
    }
    EXPECT_EQ(readText(dir / "set" / "a.txt"), "old set");
    EXPECT_FALSE(fs::exists(fresh));
    EXPECT_EQ(leftovers(dir), 0);
    fs::remove_all(dir);
}

TEST(OutputErrors, ImageRefusedInsideASetNamesTheSetsFile) {
    // The second message: "refusing to write an image with 45253 NaN/Inf pixels" naming
    // `.o3.5032.0.tmp/variance_direct.exr`. Refused images are named as the set's files now.
    const fs::path dir = testDir();
    const std::string set = (dir / "o3").string();
    Image bad(2, 2);
    bad.data[4] = std::numeric_limits<float>::infinity();
    try {
        replaceDirectory(set, [](const std::string&) { return true; },
                         [&](const std::string& staging) { writeImage(staging + "/variance_direct.exr", bad, ImageFormat::EXR); });
        ADD_FAILURE() << "an image with an infinite pixel was written";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), set + "/variance_direct.exr: refusing to write an image with 1 NaN/Inf pixel of 4; '" + set +
                                             "' was not created");
    }
    EXPECT_EQ(leftovers(dir), 0);
    fs::remove_all(dir);
}

TEST(OutputErrors, ModelSetAndReferenceEntryOnAFullDiskNameTheirDirectories) {
    const fs::path dir = testDir();
    const std::string models = (dir / "models").string();
    saveModelSet(models, tinyModelSet(1), 0x1234, std::vector<std::string>(kTinyModelInputs, "x"));
    const std::string before = readText(dir / "models" / "models.json");
    const Scene scene = cornellLike(1.f, 24);
    const ReferenceKey key = ReferenceKey::of(scene, scene.lightPosition(), 24, 24, RenderSettings());
    NoiseTarget cap;
    cap.relativeRmse = 1e-9;
    cap.sppCap = cap.sppPerPass = 2;
    {
        const FileSizeLimit limit(256);
        ASSERT_TRUE(limit.active());
        try {
            saveModelSet(models, tinyModelSet(2), 0x1234, std::vector<std::string>(kTinyModelInputs, "x"));
            ADD_FAILURE() << "a model set written under a 256-byte limit";
        } catch (const OutputError& e) {
            EXPECT_TRUE(contains(e.what(), models + "/")) << e.what();
            EXPECT_TRUE(contains(e.what(), ": write failed: File too large; the previous contents of '" + models + "' are kept"))
                << e.what();
            EXPECT_FALSE(contains(e.what(), ".tmp")) << e.what();
        }
        try {
            ReferenceStore((dir / "references").string()).obtain(scene, key, cap);
            ADD_FAILURE() << "a reference stored under a 256-byte limit";
        } catch (const InputError& e) {
            const std::string entry = (dir / "references" / key.id()).string();
            EXPECT_TRUE(contains(e.what(), entry + ": could not store the reference entry: " + entry + "/")) << e.what();
            EXPECT_TRUE(contains(e.what(), "write failed: File too large")) << e.what();
            EXPECT_FALSE(contains(e.what(), ".tmp")) << e.what();
        }
    }
    EXPECT_EQ(readText(dir / "models" / "models.json"), before);
    EXPECT_EQ(leftovers(dir), 0);
    EXPECT_EQ(leftovers(dir / "references"), 0);
    fs::remove_all(dir);
}

TEST(OutputErrors, DirectorySyncSaysWhetherItSynced) {
    const fs::path dir = testDir();
    writeFileAtomically((dir / "f").string(), "x");
    EXPECT_TRUE(syncDirectory(dir.string()));
    EXPECT_FALSE(syncDirectory((dir / "missing").string()));
    EXPECT_FALSE(syncDirectory((dir / "f").string())) << "a file is not a directory";
    fs::remove_all(dir);
}

}  // namespace test_output_errors
