// Multi-file outputs replaced as a whole (model sets, render directories), their integrity checks,
// and the clean-up of temporary files left by killed writers. Kills are real: a forked child runs
// the write with RRF_KILL_AT naming a step (core/util/temp_files.h's crashPoint) and dies of SIGKILL
// there, so no destructor or handler runs — as with `kill -9` or a power cut.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include <sys/wait.h>
#include <unistd.h>

#include "core/data/dataset_file.h"
#include "core/nn/model.h"
#include "core/nn/model_set.h"
#include "core/render/render_outputs.h"
#include "core/scene/accel.h"
#include "core/util/atomic_file.h"
#include "core/util/directory_replace.h"
#include "core/util/error.h"
#include "core/util/rng.h"
#include "core/util/temp_files.h"
#include "scene_builders.h"
#include "tests/model_builders.h"
#include "tests/test_dirs.h"

namespace test_atomic_sets {

using namespace rrf;
using namespace rrf::test;
namespace fs = std::filesystem;

namespace {

/// A scratch directory of this file's tests (tests/test_dirs.h).
struct TempDir : ScopedTempDir {
    TempDir() : ScopedTempDir("rrf_atomic_sets") {}
};

/// Runs `write` in a child process killed at `step`; true if the child died of SIGKILL there.
bool killedAt(const std::string& step, const std::function<void()>& write) {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::setenv("RRF_KILL_AT", step.c_str(), 1);
        try {
            write();
        } catch (...) {
            ::_exit(2);
        }
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

/// The pid of a process that has exited (and been reaped): no process owns it now.
long deadPid() {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    ::waitpid(pid, nullptr, 0);
    return long(pid);
}

/// Entries of `dir` whose name starts with `prefix`.
int countEntries(const fs::path& dir, const std::string& prefix) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().rfind(prefix, 0) == 0;
    return n;
}

// ---- model sets ---------------------------------------------------------------------------------

constexpr int kInputs = kTinyModelInputs;

/// Object models as in a trained set (tests/model_builders.h).
std::vector<ObjectModel> modelSet(uint64_t seed, int objects = 2) { return tinyModelSet(seed, objects); }

const std::vector<std::string> kLayout(kInputs, "x");

void save(const fs::path& dir, const std::vector<ObjectModel>& set) { saveModelSet(dir.string(), set, 0x1234, kLayout); }

/// True if the set loaded from `dir` holds exactly the networks of `expected` (every weight).
bool holds(const ModelSet& loaded, const std::vector<ObjectModel>& expected) {
    if (loaded.objects.size() != expected.size()) return false;
    for (const ObjectModel& m : expected) {
        const ObjectNetworks* o = loaded.find(m.objectId);
        if (!o || !o->has("global") || o->byTarget.at("global").leaves[0].params != m.model.leaves[0].params) return false;
    }
    return true;
}

std::string loadError(const fs::path& dir) {
    try {
        loadModelSet(dir.string(), 0x1234);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(AtomicSets, TrainKilledAtAnyStepLeavesTheOldSetOrTheNewOneNeverBoth) {
    TempDir tmp;
    const fs::path dir = tmp.path / "models";
    const std::vector<ObjectModel> oldSet = modelSet(1), newSet = modelSet(2);
    ASSERT_NE(oldSet[0].model.leaves[0].params, newSet[0].model.leaves[0].params);
    save(dir, oldSet);
    std::ofstream(dir / "notes.txt") << "a user's file beside the models";
    // Before the swap the old set must be intact; after it the new one complete.
    const std::pair<const char*, bool> steps[] = {{"commit object_0_global.rrfm", false},
                                                  {"commit object_1_global.rrfm", false},
                                                  {"commit models.json", false},
                                                  {"replace models: before swap", false},
                                                  {"replace models: after swap", true}};
    for (const auto& [step, swapped] : steps) {
        save(dir, oldSet);
        ASSERT_TRUE(killedAt(step, [&] { save(dir, newSet); })) << step;
        const ModelSet loaded = loadModelSet(dir.string(), 0x1234);
        EXPECT_TRUE(holds(loaded, swapped ? newSet : oldSet)) << step;
        EXPECT_TRUE(fs::exists(dir / "notes.txt")) << step << ": files that are not part of the set are kept";
    }
    // The killed writers' temporary directories go at the next write.
    EXPECT_GT(countEntries(tmp.path, ".models."), 0);
    save(dir, newSet);
    EXPECT_EQ(countEntries(tmp.path, ".models."), 0);
    EXPECT_TRUE(holds(loadModelSet(dir.string(), 0x1234), newSet));
}

TEST(AtomicSets, ASmallerSetReplacesTheWholeOldOne) {
    TempDir tmp;
    const fs::path dir = tmp.path / "models";
    save(dir, modelSet(1, 3));
    ASSERT_TRUE(fs::exists(dir / "object_2_global.rrfm"));
    const std::vector<ObjectModel> two = modelSet(2, 2);
    save(dir, two);
    EXPECT_FALSE(fs::exists(dir / "object_2_global.rrfm")) << "a network of the old set stayed behind";
    EXPECT_TRUE(holds(loadModelSet(dir.string(), 0x1234), two));
}

TEST(AtomicSets, ModelSetRefusesChangedMissingAndForeignFilesNamingThem) {
    TempDir tmp;
    const fs::path dir = tmp.path / "a", other = tmp.path / "b";
    save(dir, modelSet(1));
    save(other, modelSet(2));
    const std::string index = (dir / "models.json").string(), text = readFile(index);
    ASSERT_EQ(loadError(dir), "no error");

    // models.json: object 1's entry relabelled as object 0 (valid JSON, consistent otherwise).
    std::string changed = text;
    const size_t at = changed.find("\"object\": 1");
    ASSERT_NE(at, std::string::npos);
    changed[at + 10] = '0';
    writeFileAtomically(index, changed);
    EXPECT_EQ(loadError(dir), index + ": /index_checksum64: checksum mismatch: the index was changed or damaged after it "
                                      "was written (train the models again)");
    writeFileAtomically(index, text);

    // A missing model file.
    const std::string file = (dir / "object_1_global.rrfm").string(), bytes = readFile(file);
    fs::remove(file);
    EXPECT_EQ(loadError(dir), file + ": missing: listed in " + index + " at /models/1/leaves/0/file");

    // The same network's file from another set (same name, same object and target).
    fs::copy_file(other / "object_1_global.rrfm", file);
    EXPECT_EQ(loadError(dir), file + ": does not match " + index +
                                  " (/models/1/leaves/0/checksum64): the file was changed or belongs to another model set");

    // One changed byte in the weights.
    std::string flipped = bytes;
    flipped[flipped.size() - 3] ^= 0x01;
    writeFileAtomically(file, flipped);
    EXPECT_NE(loadError(dir).find(file + ": does not match"), std::string::npos);
    writeFileAtomically(file, bytes);
    EXPECT_EQ(loadError(dir), "no error");
}

TEST(AtomicSets, EverySingleBitFlipOfAModelHeaderIsRefused) {
    TempDir tmp;
    const std::string path = (tmp.path / "m.rrfm").string();
    saveModel(tinyModel(3, 5).model.leaves[0], path);
    const std::string bytes = readFile(path);
    uint32_t hlen = 0;
    std::memcpy(&hlen, bytes.data() + 12, 4);
    ASSERT_GT(hlen, 100u);
    // The preamble (magic, version, length, header checksum) and the whole JSON header.
    const size_t end = 24 + hlen;
    size_t undetected = 0;
    for (size_t bit = 0; bit < end * 8; ++bit) {
        std::string b = bytes;
        b[bit / 8] = char(b[bit / 8] ^ (1 << (bit % 8)));
        try {
            parseModel(b, path);
            ++undetected;
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), path);
        }
    }
    EXPECT_EQ(undetected, 0u) << "of " << end * 8 << " single-bit flips";
    std::printf("model header: %zu single-bit flips, %zu undetected\n", end * 8, undetected);
}

TEST(AtomicSets, HugeIntegerInAModelHeaderNamesTheField) {
    TempDir tmp;
    const std::string path = (tmp.path / "m.rrfm").string();
    saveModel(tinyModel(0, 7).model.leaves[0], path);
    const std::string bytes = readFile(path);
    uint32_t hlen = 0;
    std::memcpy(&hlen, bytes.data() + 12, 4);
    nlohmann::json h = nlohmann::json::parse(bytes.substr(24, hlen));
    h["architecture"]["inputs"] = 1e300;
    // A header with a matching checksum: the field check, not the checksum, must refuse it.
    const std::string hs = h.dump(1);
    const uint32_t n = uint32_t(hs.size());
    const uint64_t sum = checksum64(hs.data(), hs.size());
    std::string out = bytes.substr(0, 12);
    out.append(reinterpret_cast<const char*>(&n), 4);
    out.append(reinterpret_cast<const char*>(&sum), 8);
    writeFileAtomically(path, out + hs + bytes.substr(24 + hlen));
    try {
        loadModel(path);
        FAIL() << "1e300 inputs accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.where(), "header/architecture/inputs");
    }
}

TEST(AtomicSets, VersionOneModelFilesStillLoad) {
    TempDir tmp;
    const std::string path = (tmp.path / "m.rrfm").string();
    const NetworkModel net = tinyModel(0, 9).model.leaves[0];
    saveModel(net, path);
    std::string bytes = readFile(path);
    // Version 1: the same file without the header checksum.
    const uint32_t one = 1;
    std::memcpy(&bytes[8], &one, 4);
    bytes.erase(16, 8);
    EXPECT_EQ(parseModel(bytes, path).params, net.params);
}

// ---- temporary files ----------------------------------------------------------------------------

TEST(AtomicSets, StaleTemporaryFilesOfDeadWritersGoAtTheNextWrite) {
    TempDir tmp;
    const fs::path target = tmp.path / "data.bin";
    const fs::path dead = tmp.path / ("data.bin." + std::to_string(deadPid()) + ".0.tmp");
    const fs::path live = tmp.path / ("data.bin." + std::to_string(::getpid()) + ".999.tmp");
    const fs::path otherTarget = tmp.path / ("other.bin." + std::to_string(deadPid()) + ".0.tmp");
    for (const fs::path& p : {dead, live, otherTarget}) std::ofstream(p) << "partial";
    writeFileAtomically(target.string(), "new");
    EXPECT_FALSE(fs::exists(dead)) << "a dead writer's temporary stayed";
    EXPECT_TRUE(fs::exists(live)) << "a live writer's temporary was removed";
    EXPECT_TRUE(fs::exists(otherTarget)) << "another target's temporary was removed";
    EXPECT_EQ(readFile(target.string()), "new");
}

TEST(AtomicSets, KilledWriterLeavesATemporaryThatTheNextWriteRemoves) {
    TempDir tmp;
    const std::string target = (tmp.path / "out.txt").string();
    ASSERT_TRUE(killedAt("commit out.txt", [&] { writeFileAtomically(target, "half"); }));
    EXPECT_EQ(countEntries(tmp.path, "out.txt."), 1);
    EXPECT_FALSE(fs::exists(target));
    writeFileAtomically(target, "whole");
    EXPECT_EQ(countEntries(tmp.path, "out.txt."), 0);
}

TEST(AtomicSets, InterruptRemovesTheTemporaryFilesInFlight) {
    TempDir tmp;
    AtomicFile f((tmp.path / "x.bin").string());
    f.write("some bytes");
    ASSERT_TRUE(fs::exists(f.tempPath()));
    removeInFlightTemporaryFiles();
    EXPECT_FALSE(fs::exists(f.tempPath()));
    EXPECT_FALSE(fs::exists(f.path()));
}

TEST(AtomicSets, SetMovedAsideByAKilledFallbackSwapIsPutBack) {
    TempDir tmp;
    const fs::path target = tmp.path / "set";
    const fs::path aside = tmp.path / (".set." + std::to_string(deadPid()) + ".4.old");
    fs::create_directories(aside);
    std::ofstream(aside / "file") << "old set";
    EXPECT_EQ(removeStaleDirectoryTemporaries(target.string()), 1);
    EXPECT_EQ(readFile((target / "file").string()), "old set");
    EXPECT_FALSE(fs::exists(aside));
}

TEST(AtomicSets, ReplacingTheCurrentDirectoryIsRefused) {
    try {
        replaceDirectory(fs::current_path().string(), [](const std::string&) { return true; }, [](const std::string&) {});
        FAIL() << "the working directory was replaced";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("is the current directory or contains it"), std::string::npos) << e.what();
    }
}

// ---- render directories -------------------------------------------------------------------------

namespace {

const Scene& renderScene() {
    static const Scene s = cornellLike(1.f, 8);
    return s;
}

/// The bytes of every file of a render directory, by name.
std::map<std::string, std::string> filesOf(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::directory_iterator(dir))
        if (isRenderOutputEntry(e.path().filename().string())) files[e.path().filename().string()] = readFile(e.path().string());
    return files;
}

}  // namespace

TEST(AtomicSets, RenderKilledAtAnyStepLeavesTheOldImagesOrTheNewOnesNeverBoth) {
    static const Accel accel(renderScene());
    Renderer oldRender(renderScene(), accel, renderOptions(renderScene(), Estimator::NEE, 4, 2, 1));
    Renderer newRender(renderScene(), accel, renderOptions(renderScene(), Estimator::NEE, 4, 2, 2));
    oldRender.run();
    newRender.run();
    const RenderSnapshot oldSnap = oldRender.snapshot(), newSnap = newRender.snapshot();
    TempDir tmp;
    const fs::path dir = tmp.path / "render";
    auto writeOld = [&] { writeRenderOutputs(dir.string(), renderScene(), oldRender, oldSnap, ImageFormat::EXR, 0.f); };
    auto writeNew = [&] { writeRenderOutputs(dir.string(), renderScene(), newRender, newSnap, ImageFormat::EXR, 0.f); };
    writeNew();
    const auto newFiles = filesOf(dir);
    writeOld();
    const auto oldFiles = filesOf(dir);
    ASSERT_EQ(oldFiles.size(), 7u);  // 3 images, 3 variances, render.json
    ASSERT_NE(oldFiles.at("global.exr"), newFiles.at("global.exr"));
    std::ofstream(dir / "error.exr") << "not part of the render";
    const std::pair<const char*, bool> steps[] = {{"commit global.exr", false},
                                                  {"commit indirect.exr", false},
                                                  {"commit variance_global.exr", false},
                                                  {"commit render.json", false},
                                                  {"replace render: before swap", false},
                                                  {"replace render: after swap", true}};
    for (const auto& [step, swapped] : steps) {
        writeOld();
        ASSERT_TRUE(killedAt(step, writeNew)) << step;
        EXPECT_EQ(filesOf(dir), swapped ? newFiles : oldFiles) << step;
        EXPECT_TRUE(fs::exists(dir / "error.exr")) << step;
    }
    writeNew();
    EXPECT_EQ(filesOf(dir), newFiles);
    EXPECT_EQ(countEntries(tmp.path, ".render."), 0);
}

TEST(AtomicSets, RenderWithPreviewsIsOneSet) {
    static const Accel accel(renderScene());
    Renderer r(renderScene(), accel, renderOptions(renderScene(), Estimator::NEE, 1, 1, 3));
    r.run();
    TempDir tmp;
    const fs::path dir = tmp.path / "export";
    const RenderOutputs out =
        writeRenderOutputs(dir.string(), renderScene(), r, r.snapshot(), ImageFormat::EXR, 0.f, {{ImageFormat::PNG, 1.f}});
    EXPECT_EQ(out.images.size(), 6u);
    for (const char* f : {"global.exr", "direct.exr", "indirect.exr", "global.png", "direct.png", "indirect.png", "render.json"})
        EXPECT_TRUE(fs::exists(dir / f)) << f;
    EXPECT_FALSE(fs::exists(dir / "variance_global.exr")) << "1 spp: the variance is unknown";
}

TEST(AtomicSets, CliRenderKilledBeforeOrAfterTheSwapLeavesOneWholeRender) {
    TempDir tmp;
    const fs::path out = tmp.path / "r";
    const std::string project = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json";
    auto render = [&](const std::string& seed, const std::string& killAt) {
        const std::string env = killAt.empty() ? "" : "RRF_KILL_AT='" + killAt + "' ";
        return std::system((env + RRF_CLI_PATH + " render " + project + " --spp 2 --width 8 --height 8 --seed " + seed +
                            " --format exr --out " + out.string() + " >/dev/null 2>&1").c_str());
    };
    // The images and variances are deterministic; render.json also holds timings, so only its
    // seed is compared.
    auto state = [&] {
        auto files = filesOf(out);
        const nlohmann::json meta = nlohmann::json::parse(files.at("render.json"));
        files["render.json"] = meta.at("seed").dump();
        return files;
    };
    ASSERT_EQ(render("1", ""), 0);
    const auto first = state();
    ASSERT_EQ(render("2", ""), 0);
    const auto second = state();
    ASSERT_NE(first.at("global.exr"), second.at("global.exr"));
    ASSERT_EQ(render("1", ""), 0);
    EXPECT_NE(render("2", "replace r: before swap"), 0);
    EXPECT_EQ(state(), first) << "killed before the swap: the old render must be intact";
    EXPECT_NE(render("2", "replace r: after swap"), 0);
    EXPECT_EQ(state(), second) << "killed after the swap: the new render must be complete";
}

TEST(AtomicSets, CliTrainKilledBeforeOrAfterTheSwapLeavesOneWholeSet) {
    TempDir tmp;
    const std::string project = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json";
    const std::string data = (tmp.path / "d.rrfd").string();
    const fs::path models = tmp.path / "m";
    auto rrf = [](const std::string& env, const std::string& args) {
        return std::system((env + RRF_CLI_PATH + " " + args + " >/dev/null 2>&1").c_str());
    };
    ASSERT_EQ(rrf("", "generate " + project + " --grid 2,2,2 --dirs 4 --spp 2 --threads 2 --out " + data), 0);
    auto train = [&](int hidden, const std::string& killAt) {
        return rrf(killAt.empty() ? "" : "RRF_KILL_AT='" + killAt + "' ",
                   "train " + project + " --data " + data + " --hidden " + std::to_string(hidden) +
                       " --epochs 1 --threads 2 --log-every 0 --out " + models.string());
    };
    auto bytesOf = [&] {
        std::map<std::string, std::string> files;
        for (const auto& e : fs::directory_iterator(models)) files[e.path().filename().string()] = readFile(e.path().string());
        return files;
    };
    auto hiddenOfEveryNetwork = [&] {
        std::set<int> widths;
        for (const ObjectNetworks& o : loadModelSet(models.string()).objects)
            for (const auto& [target, net] : o.byTarget)
                for (const NetworkModel& leaf : net.leaves) widths.insert(leaf.arch.hidden.at(0));
        return widths;
    };
    ASSERT_EQ(train(4, ""), 0);
    const auto old = bytesOf();
    EXPECT_NE(train(5, "commit models.json"), 0);
    EXPECT_EQ(bytesOf(), old) << "killed while writing the new set: the old set must be intact";
    EXPECT_NE(train(5, "replace m: before swap"), 0);
    EXPECT_EQ(bytesOf(), old);
    EXPECT_NE(train(5, "replace m: after swap"), 0);
    EXPECT_EQ(hiddenOfEveryNetwork(), std::set<int>{5}) << "killed after the swap: the new set must be complete";
}

}  // namespace test_atomic_sets
