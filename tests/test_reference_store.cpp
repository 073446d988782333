// The reference store (core/eval/reference_store.h) on a 24×24 Cornell-like scene: a cancelled
// render resumes bit-identically, a stored reference is reused without rendering, a changed scene
// makes the old entry stale, the reached noise meets the target and agrees with the difference of
// two independent references, damaged files are InputErrors naming them, and a large measured error
// stops the render earlier.
//
// Statistical bound (ReachedNoise…). Two references r1, r2 of one truth t with independent seeds,
// each a Monte Carlo mean with per-pixel variance of the mean V1, V2: d = r1 − r2 has E[d] = 0 and
// E[d²] = V1 + V2. The renderer's estimates v1, v2 are unbiased for V1, V2 (sample variance / n), so
// per pixel q_i = Σ_c (d_c² − v1_c − v2_c)·w_c / 3 has mean 0 for any weight w independent of d. With
// w = 1/(|r̄| + 0.01)², r̄ = (r1 + r2)/2 (uncorrelated with d when V1 ≈ V2, as here: same spp), Q =
// mean_i q_i is 0 in expectation; pixels are independent, so its standard error is sd(q_i)/√pixels and
// |Q| < 5·SE unless the variances (hence the noise figure built from them) are wrong. Q is also
// compared with the figure itself: mean(d²·w) against n1² + n2² (the two references' reported
// relative noise squared) within the same 5·SE plus the difference of the weights (|r1| vs |r̄|).
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/data/record_layout.h"
#include "core/eval/error_metrics.h"
#include "core/eval/reference_file.h"
#include "core/eval/reference_settings_json.h"
#include "core/eval/reference_store.h"
#include "core/project/project.h"
#include "core/predict/gbuffer.h"
#include "core/project/project_file.h"
#include "core/scene/accel.h"
#include "core/util/error.h"
#include "scene_builders.h"
#include "tests/cli_runner.h"

namespace test_reference_store {

using namespace rrf;
using namespace rrf::test;

namespace fs = std::filesystem;

namespace {

constexpr int kSize = 24;

/// A fresh store directory per test (removed at the end).
struct TempStore {
    fs::path dir;
    explicit TempStore(const std::string& name)
        : dir(fs::temp_directory_path() / ("rrf_refstore_" + name + "_" + std::to_string(::getpid()))) {
        fs::remove_all(dir);
    }
    ~TempStore() { fs::remove_all(dir); }
    ReferenceStore store() const { return ReferenceStore(dir.string()); }
};

Scene scene() { return cornellLike(1.f, kSize); }

ReferenceKey keyOf(const Scene& s, uint64_t seed = 1) {
    RenderSettings r;
    r.seed = seed;
    return ReferenceKey::of(s, s.lightPosition(), kSize, kSize, r);
}

/// A target no render reaches: every render runs to the cap.
NoiseTarget toCap(int cap, int perPass) {
    NoiseTarget t;
    t.relativeRmse = 1e-9;
    t.sppCap = cap;
    t.sppPerPass = perPass;
    return t;
}

bool sameBits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.data.size() == b.data.size() &&
           std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

bool sameReference(const Reference& a, const Reference& b) {
    for (Term t : kTerms)
        if (!sameBits(a.image(t), b.image(t)) || !sameBits(a.variance(t), b.variance(t))) return false;
    return a.spp == b.spp;
}

struct Log {
    std::vector<std::string> lines;
    std::function<void(const std::string&)> fn() {
        return [this](const std::string& m) { lines.push_back(m); };
    }
    bool contains(const std::string& word) const {
        for (const std::string& l : lines)
            if (l.find(word) != std::string::npos) return true;
        return false;
    }
};

FootprintMask maskOf(const Scene& s) {
    const Accel accel(s);
    const PathTracer tracer(s, accel, Estimator::NEE, 1);
    return footprintMask(buildGBuffer(tracer, RecordLayout::forScene(s), s.lightPosition(), kSize, kSize));
}

}  // namespace

TEST(Renderer, RestoredStateContinuesBitIdentically) {
    // 8 spp straight, against 2 + 2 passes exported, restored into a new renderer and continued by 4:
    // sums run in sample order whatever the split, so the bits agree.
    const Scene s = scene();
    const Accel accel(s);
    RenderOptions o;
    o.width = o.height = kSize;
    o.spp = 8;
    o.samplesPerPass = 8;
    Renderer straight(s, accel, o);
    straight.run();
    o.samplesPerPass = 2;
    Renderer first(s, accel, o);
    ASSERT_TRUE(first.runPass());
    ASSERT_TRUE(first.runPass());
    const RenderState saved = first.exportState();
    EXPECT_EQ(saved.sppDone, 4);
    o.samplesPerPass = 4;
    Renderer second(s, accel, o);
    second.restoreState(saved);
    second.run();
    const RenderSnapshot a = straight.snapshot(), b = second.snapshot();
    EXPECT_EQ(b.sppCompleted, 8);
    EXPECT_TRUE(sameBits(a.global, b.global));
    EXPECT_TRUE(sameBits(a.direct, b.direct));
    EXPECT_TRUE(sameBits(a.variance, b.variance));
    EXPECT_TRUE(sameBits(a.indirectVariance, b.indirectVariance));
    EXPECT_EQ(a.samples, b.samples);
}

TEST(ReferenceStore, ResumeAfterCancelEqualsAnUninterruptedRender) {
    const Scene s = scene();
    const ReferenceKey key = keyOf(s);
    const NoiseTarget target = toCap(1024, 8);
    TempStore interrupted("cancel"), straight("straight");
    ReferenceStore store = interrupted.store();
    // Cancelled once 64 spp are done (from the progress report, so the test does not depend on the
    // machine's speed): the next pass is cut or never started.
    std::atomic<bool> cancel{false};
    const auto progress = [&](const ReferenceProgress& p) {
        if (p.spp >= 64) cancel = true;
    };
    Log log;
    const Reference partial = store.obtain(s, key, target, &cancel, progress, {}, log.fn());
    ASSERT_TRUE(partial.cancelled) << "cancelled at 64 of 1024 spp";
    const std::optional<StoredReference> saved = store.find(key);
    ASSERT_TRUE(saved.has_value()) << "a cancelled render is saved";
    EXPECT_FALSE(saved->complete);
    EXPECT_GT(saved->spp, 0);
    EXPECT_LT(saved->spp, target.sppCap);
    EXPECT_EQ(saved->spp % target.sppPerPass, 0) << "the cut pass is dropped: the sums end on a pass boundary";
    EXPECT_TRUE(log.contains("cancelled"));

    Log resumeLog;
    const Reference resumed = store.obtain(s, key, target, nullptr, {}, {}, resumeLog.fn());
    EXPECT_TRUE(resumeLog.contains("continuing")) << "resumed from the saved sums";
    EXPECT_FALSE(resumed.cancelled);
    EXPECT_EQ(resumed.spp, target.sppCap);
    const Reference whole = straight.store().obtain(s, key, target);
    EXPECT_TRUE(sameReference(resumed, whole));
    // And an independent computation: the renderer in one pass of 1024 samples.
    const Accel accel(s);
    RenderOptions o;
    o.width = o.height = kSize;
    o.spp = o.samplesPerPass = target.sppCap;
    Renderer once(s, accel, o);
    once.run();
    EXPECT_TRUE(sameBits(once.snapshot().global, resumed.image(Term::Global)));
    EXPECT_TRUE(store.find(key)->complete);
}

TEST(ReferenceStore, SecondObtainReusesWithoutRendering) {
    const Scene s = scene();
    const ReferenceKey key = keyOf(s);
    const NoiseTarget target = toCap(64, 16);
    TempStore t("reuse");
    ReferenceStore store = t.store();
    Log first, second;
    const Reference a = store.obtain(s, key, target, nullptr, {}, {}, first.fn());
    EXPECT_TRUE(first.contains("rendering"));
    int progressCalls = 0;
    const Reference b = store.obtain(s, key, target, nullptr, [&](const ReferenceProgress&) { ++progressCalls; }, {}, second.fn());
    EXPECT_TRUE(second.contains("reusing")) << "never silent";
    EXPECT_FALSE(second.contains("rendering"));
    EXPECT_EQ(progressCalls, 0) << "no pass ran";
    EXPECT_EQ(a.seconds, b.seconds) << "no render time added";
    EXPECT_TRUE(sameReference(a, b));
    // The entry is a directory rrf evaluate --reference reads.
    const Reference loaded = loadReference(store.find(key)->dir);
    EXPECT_TRUE(sameBits(loaded.image(Term::Global), a.image(Term::Global)));
    EXPECT_TRUE(sameBits(loaded.variance(Term::Indirect), a.variance(Term::Indirect)));
    EXPECT_EQ(loaded.spp, 64);
}

TEST(ReferenceStore, ChangedSceneGetsANewKeyAndItsOldEntryIsStale) {
    Scene s = scene();
    TempStore t("stale");
    ReferenceStore store = t.store();
    const ReferenceKey before = keyOf(s);
    store.obtain(s, before, toCap(4, 4));
    s.materials[0].kd = Vec3(0.5f, 0.5f, 0.5f);  // the walls' albedo, as the workbench's material edit does
    const ReferenceKey after = keyOf(s);
    EXPECT_NE(before.id(), after.id());
    EXPECT_FALSE(store.find(after).has_value()) << "never used for the edited scene";
    std::vector<StoredReference> listed = store.list(s.contentHash());
    ASSERT_EQ(listed.size(), 1u);
    EXPECT_TRUE(listed[0].stale);
    EXPECT_EQ(listed[0].key.id(), before.id());
    store.obtain(s, after, toCap(4, 4));
    listed = store.list(s.contentHash());
    ASSERT_EQ(listed.size(), 2u);
    EXPECT_EQ(store.pruneStale(s.contentHash()), 1);
    listed = store.list(s.contentHash());
    ASSERT_EQ(listed.size(), 1u);
    EXPECT_FALSE(listed[0].stale);
    EXPECT_EQ(listed[0].key.id(), after.id());
}

TEST(ReferenceStore, ReachedNoiseMeetsTheTargetAndAgreesWithTwoIndependentReferences) {
    const Scene s = scene();
    NoiseTarget target;
    target.relativeRmse = 0.05;
    target.sppCap = 8192;
    target.sppPerPass = 16;
    TempStore t("noise");
    ReferenceStore store = t.store();
    const ReferenceKey k1 = keyOf(s, 1), k2 = keyOf(s, 2);
    const Reference r1 = store.obtain(s, k1, target), r2 = store.obtain(s, k2, target);
    const StoredReference e1 = *store.find(k1), e2 = *store.find(k2);
    for (const StoredReference* e : {&e1, &e2}) {
        const double n = e->noise.relativeRmse[int(Term::Global)];
        EXPECT_TRUE(n <= target.relativeRmse || e->spp == target.sppCap) << n << " at " << e->spp << " spp";
        EXPECT_LT(e->spp, target.sppCap) << "0.05 is reached well below the cap at 24x24";
        EXPECT_TRUE(e->complete);
    }
    // The independent check: E[(r1 − r2)²] = V1 + V2 (file comment).
    const std::vector<uint32_t>& mask = maskOf(s).kept;
    ASSERT_GT(mask.size(), 100u);
    for (Term term : kTerms) {
        const Image &a = r1.image(term), &b = r2.image(term), &va = r1.variance(term), &vb = r2.variance(term);
        std::vector<double> q;
        double sumD2w = 0, floorA = 0, floorB = 0;
        for (uint32_t i : mask) {
            double qi = 0;
            for (int c = 0; c < 3; ++c) {
                const size_t k = 3 * size_t(i) + size_t(c);
                const double d = double(a.data[k]) - b.data[k];
                const double mean = 0.5 * (double(a.data[k]) + b.data[k]);
                const double w = 1.0 / ((std::fabs(mean) + kRelativeEpsilon) * (std::fabs(mean) + kRelativeEpsilon));
                qi += (d * d - va.data[k] - vb.data[k]) * w / 3.0;
                sumD2w += d * d * w;
                floorA += va.data[k] / std::pow(std::fabs(a.data[k]) + kRelativeEpsilon, 2);
                floorB += vb.data[k] / std::pow(std::fabs(b.data[k]) + kRelativeEpsilon, 2);
            }
            q.push_back(qi);
        }
        double mean = 0, var = 0;
        for (double v : q) mean += v / double(q.size());
        for (double v : q) var += (v - mean) * (v - mean) / double(q.size() - 1);
        const double se = std::sqrt(var / double(q.size()));
        EXPECT_LT(std::fabs(mean), 5 * se) << termName(term) << ": the variances explain the difference";
        // The store's figures are sqrt(mean v / (|r| + ε)²); their squares add up to the empirical one.
        const double n1 = e1.noise.relativeRmse[int(term)], n2 = e2.noise.relativeRmse[int(term)];
        const size_t n = 3 * mask.size();
        EXPECT_NEAR(n1 * n1, floorA / double(n), 1e-6 * n1 * n1) << "the stored noise is the reference's own floor";
        EXPECT_NEAR(n2 * n2, floorB / double(n), 1e-6 * n2 * n2);
        const double empirical = sumD2w / double(n), predicted = n1 * n1 + n2 * n2;
        std::printf("%s: empirical mean d²w %.4g, n1²+n2² %.4g (noise %.4f, %.4f), Q %.3g, SE %.3g\n", termName(term), empirical,
                    predicted, n1, n2, mean, se);
        EXPECT_NEAR(empirical, predicted, 5 * se + 0.25 * predicted) << termName(term);
    }
}

TEST(ReferenceStore, DamagedFilesAreInputErrorsNamingThem) {
    const Scene s = scene();
    const ReferenceKey key = keyOf(s);
    TempStore t("damaged");
    ReferenceStore store = t.store();
    store.obtain(s, key, toCap(4, 4));
    const fs::path dir = store.find(key)->dir;
    const fs::path state = dir / "state.rrfs";
    auto expectInputError = [&](const std::string& file) {
        try {
            store.obtain(s, key, toCap(4, 4));
            ADD_FAILURE() << "no error for a damaged " << file;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
        }
    };
    {  // one flipped byte in the pixel sums
        std::fstream f(state, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(200);
        char c = 0;
        f.read(&c, 1);
        f.seekp(200);
        c = char(c ^ 0x40);
        f.write(&c, 1);
    }
    expectInputError("state.rrfs");
    fs::resize_file(state, fs::file_size(state) / 2);
    expectInputError("state.rrfs");
    std::ofstream(dir / "reference.json") << "{ \"format\": \"rrf reference 1\", ";
    expectInputError("reference.json");
    const std::vector<StoredReference> listed = store.list(s.contentHash());
    ASSERT_EQ(listed.size(), 1u);
    EXPECT_NE(listed[0].problem.find("reference.json"), std::string::npos) << "listed with its problem, not a crash";
    EXPECT_EQ(store.pruneStale(s.contentHash()), 1);
    EXPECT_FALSE(store.find(key).has_value());
}

TEST(ReferenceStore, ALargeMeasuredErrorStopsEarlier) {
    // wanted = max(0.01, 0.25 × error): an error of 0.4 needs a noise of 0.1 only.
    const Scene s = scene();
    NoiseTarget target;
    target.relativeRmse = 0.01;
    target.errorFraction = 0.25;
    target.sppCap = 1024;
    target.sppPerPass = 8;
    TempStore t("hook");
    ReferenceStore store = t.store();
    const ReferenceKey k1 = keyOf(s, 1), k2 = keyOf(s, 2);
    store.obtain(s, k1, target);
    int calls = 0;
    store.obtain(s, k2, target, nullptr, {}, [&](const Reference& r) {
        ++calls;
        EXPECT_EQ(r.image(Term::Global).width, kSize) << "the hook sees the reference so far";
        return 0.4;
    });
    const StoredReference strict = *store.find(k1), loose = *store.find(k2);
    EXPECT_GT(calls, 0);
    EXPECT_LT(loose.spp, strict.spp);
    const double n = loose.noise.relativeRmse[int(Term::Global)];
    EXPECT_LE(n, 0.1);
    EXPECT_GT(n, 0.01) << "it stopped at 0.1, not at the target";
    EXPECT_NEAR(loose.wantedNoise, 0.1, 1e-12);
    // One pass earlier it was still above 0.1: noise ∝ 1/√spp.
    EXPECT_GT(n * std::sqrt(double(loose.spp) / double(loose.spp - target.sppPerPass)), 0.1 * 0.97);
}

TEST(ReferenceSettings, ProjectSectionIsParsedStrictlyAndRoundTrips) {
    const fs::path dir = fs::temp_directory_path() / ("rrf_refsettings_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string cornell = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/scene.json";
    auto write = [&](const std::string& section) {
        const std::string path = (dir / "project.json").string();
        std::ofstream(path) << "{\"rrf_project\": 1, \"scene\": \"" << cornell << "\", \"reference\": " << section << "}";
        return path;
    };
    const Project p = loadProjectOrScene(write(R"({"noise": 0.02, "error_fraction": 0.5, "spp_cap": 512, "spp_per_pass": 8,
                                                   "width": 64, "height": 48})"));
    EXPECT_EQ(p.reference.target.relativeRmse, 0.02);
    EXPECT_EQ(p.reference.target.errorFraction, 0.5);
    EXPECT_EQ(p.reference.target.sppCap, 512);
    EXPECT_EQ(p.reference.target.sppPerPass, 8);
    EXPECT_EQ(p.reference.width, 64);
    EXPECT_EQ(p.reference.height, 48);
    EXPECT_EQ(p.reference.target.wanted(0.2), 0.1) << "max(0.02, 0.5 x 0.2)";
    EXPECT_EQ(p.reference.target.wanted(0.01), 0.02);
    Project copy = p;
    saveProject(copy, (dir / "saved.json").string());
    const Project q = loadProjectOrScene((dir / "saved.json").string());
    EXPECT_EQ(toJson(q.reference), toJson(p.reference));
    const std::vector<std::pair<std::string, std::string>> bad = {
        {R"({"noize": 0.01})", "/reference/noize"},
        {R"({"noise": 0})", "/reference/noise"},
        {R"({"spp_cap": 1})", "/reference/spp_cap"},
        {R"({"error_fraction": 2})", "/reference/error_fraction"},
        {R"({"spp_per_pass": "16"})", "/reference/spp_per_pass"},
    };
    for (const auto& [section, pointer] : bad) {
        try {
            loadProjectOrScene(write(section));
            ADD_FAILURE() << section << " accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.where(), pointer) << e.what();
            EXPECT_NE(e.file().find("project.json"), std::string::npos) << e.what();
        }
    }
    fs::remove_all(dir);
}

TEST(ReferenceCli, RendersReusesListsAndPrunes) {
    // rrf reference on a copy of the Cornell box at 16x16: render, reuse, then an edited material
    // makes the entry stale, --list says so and --prune removes it.
    const fs::path dir = fs::temp_directory_path() / ("rrf_refcli_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path src = fs::path(RRF_SOURCE_DIR) / "projects" / "cornell-box";
    fs::copy_file(src / "project.json", dir / "project.json");
    fs::copy_file(src / "scene.json", dir / "scene.json");
    const std::string project = (dir / "project.json").string();
    const std::string args = "reference " + project + " --width 16 --height 16 --noise 0.2 --threads 2";
    const test::CliResult first = test::runCli(args);
    ASSERT_EQ(first.code, 0) << first.output;
    EXPECT_NE(first.output.find("rendering 16x16"), std::string::npos) << first.output;
    EXPECT_NE(first.output.find("relative noise direct"), std::string::npos) << "reached noise per term printed";
    const test::CliResult second = test::runCli(args);
    ASSERT_EQ(second.code, 0) << second.output;
    EXPECT_NE(second.output.find("reusing the stored reference"), std::string::npos) << second.output;
    EXPECT_EQ(second.output.find("rendering"), std::string::npos) << second.output;
    // Edit the white material's albedo.
    std::string scene;
    {
        std::ifstream in(dir / "scene.json");
        scene.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const size_t at = scene.find("0.885809");
    ASSERT_NE(at, std::string::npos);
    scene.replace(at, 8, "0.5");
    std::ofstream(dir / "scene.json") << scene;
    const test::CliResult listed = test::runCli("reference " + project + " --list");
    ASSERT_EQ(listed.code, 0) << listed.output;
    EXPECT_NE(listed.output.find("1 reference(s)"), std::string::npos) << listed.output;
    EXPECT_NE(listed.output.find("stale"), std::string::npos) << listed.output;
    const test::CliResult pruned = test::runCli("reference " + project + " --prune --list");
    ASSERT_EQ(pruned.code, 0) << pruned.output;
    EXPECT_NE(pruned.output.find("removed 1 stale"), std::string::npos) << pruned.output;
    EXPECT_NE(pruned.output.find("0 reference(s)"), std::string::npos) << pruned.output;
    fs::remove_all(dir);
}

}  // namespace test_reference_store
