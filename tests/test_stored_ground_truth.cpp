// The workbench's stored ground truth (core/eval/stored_ground_truth_file.h): a stored render is exactly
// the render a new one of the same key and spp gives (checked against an independent second render,
// not against what was written), another key or spp is never used, and a damaged set says why.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "core/eval/stored_ground_truth_file.h"
#include "core/render/render_settings.h"
#include "core/scene/accel.h"
#include "scene_builders.h"

namespace test_stored_ground_truth {

namespace fs = std::filesystem;
using namespace rrf;
using rrf::test::cornellLike;
using rrf::test::renderOptions;

struct Dir {
    fs::path path;
    Dir() {
        static int counter = 0;
        path = fs::temp_directory_path() / ("rrf_stored_gt_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        fs::remove_all(path);
    }
    ~Dir() { fs::remove_all(path); }
};

struct Rendered {
    RenderSnapshot snapshot;
    RenderStats stats;
};

Rendered renderOf(const Scene& scene, int spp) {
    const Accel accel(scene);
    Renderer r(scene, accel, renderOptions(scene, Estimator::NEE, spp, 1));
    r.run();
    return {r.snapshot(), r.stats()};
}

void store(const fs::path& dir, const ReferenceKey& key, const Rendered& r) {
    storeGroundTruth(dir.string(), key, r.snapshot, r.stats);
}

ReferenceKey keyOf(const Scene& scene) {
    RenderSettings s;
    s.estimator = Estimator::NEE;
    return ReferenceKey::of(scene, scene.lightPosition(), scene.camera.width, scene.camera.height, s);
}

bool sameBits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.data.size() == b.data.size() &&
           std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(a.data[0])) == 0;
}

}  // namespace test_stored_ground_truth

using namespace test_stored_ground_truth;

TEST(StoredGroundTruth, LoadsExactlyWhatAFreshRenderOfTheSameKeyGives) {
    const Scene scene = cornellLike(1.f, 8);
    const Dir dir;
    EXPECT_FALSE(loadGroundTruth(dir.path.string(), keyOf(scene), 4).snapshot) << "nothing stored yet";
    EXPECT_TRUE(loadGroundTruth(dir.path.string(), keyOf(scene), 4).why.empty()) << "a first render needs no reason";
    store(dir.path, keyOf(scene), renderOf(scene, 4));
    const StoredGroundTruth got = loadGroundTruth(dir.path.string(), keyOf(scene), 4);
    ASSERT_TRUE(got.snapshot) << got.why;
    // An independent render of the same key: the renderer's determinism is what makes storing exact.
    const Rendered render = renderOf(scene, 4);
    const RenderSnapshot& fresh = render.snapshot;
    for (Term t : kTerms) {
        EXPECT_TRUE(sameBits(got.snapshot->image(t), fresh.image(t))) << termName(t);
        EXPECT_TRUE(sameBits(got.snapshot->varianceOf(t), fresh.varianceOf(t))) << termName(t) << " variance";
    }
    EXPECT_EQ(got.snapshot->sppCompleted, 4);
    EXPECT_EQ(got.snapshot->samples, fresh.samples);
    EXPECT_TRUE(got.snapshot->varianceKnown());
    EXPECT_EQ(got.stats.rays, render.stats.rays) << "the statistics a saved run's render.json reports";
    EXPECT_EQ(got.stats.shadowRays, render.stats.shadowRays);
    EXPECT_GT(got.stats.rays, 0u);
}

TEST(StoredGroundTruth, AnotherLightSizeOrSppIsNeverUsed) {
    Scene scene = cornellLike(1.f, 8);
    const Dir dir;
    store(dir.path, keyOf(scene), renderOf(scene, 2));
    const StoredGroundTruth moreSpp = loadGroundTruth(dir.path.string(), keyOf(scene), 8);
    EXPECT_FALSE(moreSpp.snapshot);
    EXPECT_NE(moreSpp.why.find("2 spp, 8 are asked for"), std::string::npos) << moreSpp.why;
    Scene moved = scene;
    moved.setLightPosition(scene.lightPosition() + Vec3(0.05f, 0.f, 0.f));
    const StoredGroundTruth otherLight = loadGroundTruth(dir.path.string(), keyOf(moved), 2);
    EXPECT_FALSE(otherLight.snapshot);
    EXPECT_NE(otherLight.why.find("another scene, light"), std::string::npos) << otherLight.why;
    Scene bigger = scene;
    bigger.camera.width = 16;
    EXPECT_FALSE(loadGroundTruth(dir.path.string(), keyOf(bigger), 2).snapshot);
}

TEST(StoredGroundTruth, ANewRenderReplacesTheOldSetWhole) {
    const Scene scene = cornellLike(1.f, 8);
    const Dir dir;
    store(dir.path, keyOf(scene), renderOf(scene, 4));
    ASSERT_TRUE(fs::exists(dir.path / "variance_global.exr"));
    // 1 spp has no variance: the old set's variance images must not survive beside the new images.
    store(dir.path, keyOf(scene), renderOf(scene, 1));
    EXPECT_FALSE(fs::exists(dir.path / "variance_global.exr"));
    const StoredGroundTruth got = loadGroundTruth(dir.path.string(), keyOf(scene), 1);
    ASSERT_TRUE(got.snapshot) << got.why;
    EXPECT_FALSE(got.snapshot->varianceKnown());
    EXPECT_FALSE(loadGroundTruth(dir.path.string(), keyOf(scene), 4).snapshot);
}

TEST(StoredGroundTruth, DamagedFilesAreReportedByNameAndNotUsed) {
    const Scene scene = cornellLike(1.f, 8);
    const Dir dir;
    store(dir.path, keyOf(scene), renderOf(scene, 2));
    std::ofstream(dir.path / "global.exr", std::ios::binary | std::ios::trunc) << "not an image";
    const StoredGroundTruth broken = loadGroundTruth(dir.path.string(), keyOf(scene), 2);
    EXPECT_FALSE(broken.snapshot);
    EXPECT_NE(broken.why.find("global.exr"), std::string::npos) << broken.why;

    std::ofstream(dir.path / "ground_truth.json", std::ios::trunc) << "{\"format\": \"rrf-ground-truth-1\", \"spp\": \"many\"}";
    const StoredGroundTruth badMeta = loadGroundTruth(dir.path.string(), keyOf(scene), 2);
    EXPECT_FALSE(badMeta.snapshot);
    EXPECT_NE(badMeta.why.find("ground_truth.json"), std::string::npos) << badMeta.why;
}
