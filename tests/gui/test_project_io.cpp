// Save -> reopen round trips of everything the workbench keeps in a project, and the pure logic
// behind the panels (runs, scene overrides, energy conservation, layout, file dialog, view model).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/project/pane_layout_json.h"
#include "core/project/runs_json.h"
#include "panels/file_dialog.h"
#include "panels/project_io.h"
#include "core/project/scene_edits.h"
#include "panels/view_model.h"

namespace rrf::test::test_project_io {

namespace fs = std::filesystem;
using namespace rrf::panels;

namespace {
const fs::path kCornellDir = RRF_SOURCE_DIR "/projects/cornell-box";

/// A private copy of the Cornell-box project (tests never write into the source tree).
fs::path copyCornell(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("rrf_gui_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file(kCornellDir / "project.json", dir / "project.json");
    fs::copy_file(kCornellDir / "scene.json", dir / "scene.json");
    return dir;
}

rrf::Run sampleRun(const std::string& id) {
    rrf::Run r;
    r.id = id;
    r.name = "run " + id;
    r.kind = "train";
    r.created = "2024-01-02T03:04:05";
    r.settings.render = RenderSettings();
    r.settings.render->spp = 16;
    r.settings.other = jsonText({{"hidden", {20, 10}}});  // a key a newer workbench wrote
    r.loss = {{0, 1.0, 2.0, 0.0}, {1, 0.5, std::numeric_limits<double>::quiet_NaN(), 0.25}};
    r.metrics.rmse = 0.125;
    r.metrics.other = jsonText({{"future_metric", 2}});
    r.timings.train = 3.5;
    r.artifacts = {"runs/" + id + "/model.rrfm"};
    r.extra = jsonText({{"future_key", {{"x", 1}}}});
    return r;
}
}  // namespace

TEST(ProjectIo, SaveAndReopenKeepsEverySettingAndRun) {
    const fs::path dir = copyCornell("roundtrip");
    WorkbenchState a;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(a, (dir / "project.json").string(), error)) << error;

    a.project.name = "round trip";
    a.project.render.spp = 123;
    a.project.render.seed = 77;
    a.project.render.estimator = Estimator::Naive;
    a.project.render.maxDepth = 9;
    a.project.render.width = 64;
    a.project.render.height = 48;
    a.view.exposure = 1.5f;
    a.project.layout.root = PaneLayout::defaultRoot(0.4f, 0.2f);
    a.project.runs = {sampleRun("a"), sampleRun("b")};
    Material white = a.project.scene.materials[0];
    white.kd = Vec3(0.3f, 0.4f, 0.5f);
    white.ks = Vec3(0.2f, 0.1f, 0.f);
    white.exponent = 42.f;
    editMaterial(a.project, 0, white, true);  // as the Scene panel does
    moveLight(a.project, Vec3(0.25f, 0.8f, -0.125f));
    SamplingSettings sampling;
    sampling.nz = 4;
    a.project.sampling = sampling;  // another module's section survives too
    a.dirty = true;

    const std::string saved = (dir / "saved.json").string();
    ASSERT_TRUE(saveStateToProject(a, saved, error)) << error;
    EXPECT_FALSE(a.dirty);

    WorkbenchState b;
    ASSERT_TRUE(loadProjectIntoState(b, saved, error)) << error;
    EXPECT_EQ(b.projectName(), "round trip");
    EXPECT_EQ(b.project.render.spp, 123);
    EXPECT_EQ(b.project.render.seed, 77u);
    EXPECT_EQ(b.project.render.estimator, Estimator::Naive);
    EXPECT_EQ(b.project.render.maxDepth, 9);
    EXPECT_EQ(b.project.render.width, 64);
    EXPECT_EQ(b.project.render.height, 48);
    EXPECT_FLOAT_EQ(b.view.exposure, 1.5f);
    EXPECT_FLOAT_EQ(b.project.layout.root.fraction, 0.4f);
    EXPECT_FLOAT_EQ(1.f - b.project.layout.root.children[1].fraction, 0.2f);
    ASSERT_EQ(b.project.runs.size(), 2u);
    for (size_t i = 0; i < 2; ++i) EXPECT_EQ(toJson(b.project.runs[i]), toJson(a.project.runs[i]));
    EXPECT_TRUE(std::isnan(b.project.runs[0].loss[1].validation));
    EXPECT_EQ(parseJsonText(b.project.runs[0].extra)["future_key"]["x"], 1);
    const Material& w = b.project.scene.materials[0];
    EXPECT_FLOAT_EQ(w.kd.y, 0.4f);
    EXPECT_FLOAT_EQ(w.ks.x, 0.2f);
    EXPECT_FLOAT_EQ(w.exponent, 42.f);
    EXPECT_EQ(w.type, Material::Type::Phong);
    const Vec3 p = b.project.scene.lightPosition();
    EXPECT_FLOAT_EQ(p.x, 0.25f);
    EXPECT_FLOAT_EQ(p.y, 0.8f);
    EXPECT_FLOAT_EQ(p.z, -0.125f);
    ASSERT_TRUE(b.project.sampling.has_value());
    EXPECT_EQ(b.project.sampling->nz, 4);
    EXPECT_EQ(b.project.scene.contentHash(), a.project.scene.contentHash());
    fs::remove_all(dir);
}

TEST(ProjectIo, BadFileKeepsTheOpenProject) {
    const fs::path dir = copyCornell("bad");
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, (dir / "project.json").string(), error)) << error;
    s.dirty = true;
    std::ofstream(dir / "broken.json") << "{ \"rrf_project\": 1, \"scene\": ";
    EXPECT_FALSE(loadProjectIntoState(s, (dir / "broken.json").string(), error));
    EXPECT_NE(error.find("broken.json"), std::string::npos) << error;
    EXPECT_FALSE(loadProjectIntoState(s, (dir / "missing.json").string(), error));
    EXPECT_TRUE(s.hasProject);
    EXPECT_TRUE(s.dirty) << "a failed open must not touch the open project";
    EXPECT_EQ(s.projectName(), "Cornell box");
    fs::remove_all(dir);
}

TEST(ProjectIo, MalformedSettingsSectionIsRefusedAtLoadAndTheOpenProjectKept) {
    // A bad value in a settings section is reported when the file is opened (file, JSON pointer,
    // what was expected), no longer when a panel first draws it: the workbench shows the message
    // and keeps the project it had open.
    const fs::path dir = copyCornell("malformed");
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, (dir / "project.json").string(), error)) << error;
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(dir / "project.json"));
    doc["sampling"] = {{"grid", {4, "four", 4}}};
    std::ofstream(dir / "bad_sampling.json") << doc.dump(2);
    EXPECT_FALSE(loadProjectIntoState(s, (dir / "bad_sampling.json").string(), error));
    EXPECT_NE(error.find("bad_sampling.json: /sampling/grid/1: expected integer, got string"), std::string::npos)
        << error;
    EXPECT_TRUE(s.hasProject);
    EXPECT_EQ(s.project.path, (dir / "project.json").string());
    fs::remove_all(dir);
}

TEST(ProjectIo, FailedSaveChangesNothing) {
    const fs::path dir = copyCornell("failsave");
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, (dir / "project.json").string(), error)) << error;
    s.dirty = true;
    EXPECT_FALSE(saveStateToProject(s, (dir / "no-such-dir" / "x.json").string(), error));
    EXPECT_TRUE(s.dirty);
    EXPECT_EQ(s.project.path, (dir / "project.json").string());
    fs::remove_all(dir);
}

TEST(ProjectIo, DamagedWorkbenchSectionsAreReportedNotFatal) {
    const fs::path dir = copyCornell("damaged");
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(dir / "project.json"));
    doc["layout"] = {{"left", "wide"}, {"bottom", 5.0}};
    doc["runs"] = nlohmann::json::array({toJson(sampleRun("ok")), {{"name", "no id"}}});
    doc["scene_overrides"] = {{"light_position", {9, 9, 9}}, {"materials", {{"nope", {{"kd", {1, 1, 1}}}}}}};
    std::ofstream(dir / "project.json") << doc.dump(2);
    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, (dir / "project.json").string(), error)) << error;
    EXPECT_EQ(s.project.runs.size(), 1u);
    EXPECT_FLOAT_EQ(s.project.layout.root.fraction, PaneLayout::kDefaultLeft);
    EXPECT_FLOAT_EQ(1.f - s.project.layout.root.children[1].fraction, PaneLayout::kMaxFraction);
    EXPECT_TRUE(s.project.scene.lightRegion.contains(s.project.scene.lightPosition()));
    EXPECT_GE(s.log.entries().size(), 4u) << s.log.text();
    fs::remove_all(dir);
}

TEST(SceneOverrides, EnergyConservationLowersTheOtherCoefficient) {
    Material m;
    m.kd = Vec3(0.9f, 0.5f, 0.2f);
    m.ks = Vec3(0.3f, 0.5f, 0.9f);
    EXPECT_TRUE(enforceEnergyConservation(m, true));
    EXPECT_FLOAT_EQ(m.kd.x, 0.9f);
    EXPECT_NEAR(m.ks.x, 0.1f, 1e-6f);
    EXPECT_FLOAT_EQ(m.ks.y, 0.5f);
    EXPECT_NEAR(m.ks.z, 0.8f, 1e-6f);
    m.kd = Vec3(2.f, -1.f, std::nanf(""));
    enforceEnergyConservation(m, false);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GE(m.kd[c], 0.f);
        EXPECT_LE(m.kd[c] + m.ks[c], 1.f + 1e-6f);
    }
    Material ok;
    ok.kd = Vec3(0.5f);
    EXPECT_FALSE(enforceEnergyConservation(ok, true));
}

TEST(Layout, JsonRoundTripAndReset) {
    std::vector<std::string> warnings;
    auto read = [&](const nlohmann::json& j) { return paneLayoutFromJson(JsonReader(j, "p.json", "/layout"), warnings); };
    PaneLayout l;
    l.root = PaneLayout::defaultRoot(0.5f, 0.1f);
    EXPECT_EQ(read(toJson(l)), l);
    l.reset();
    EXPECT_EQ(l, PaneLayout());
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(read(nlohmann::json("garbage")), PaneLayout());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("p.json: /layout: expected an object, got string"), std::string::npos) << warnings[0];
}

TEST(Runs, IdsAreUnique) {
    std::vector<rrf::Run> runs;
    for (int i = 0; i < 3; ++i) {
        rrf::Run r;
        r.id = newRunId(runs, "render");
        runs.push_back(r);
    }
    EXPECT_NE(runs[0].id, runs[1].id);
    EXPECT_NE(runs[1].id, runs[2].id);
    EXPECT_EQ(runs[0].id.rfind("render-", 0), 0u);
}

TEST(FileDialog, ConfirmChecksThePath) {
    const fs::path dir = copyCornell("dialog");
    FileDialog d;
    d.open(FileDialog::Mode::Open, "Open", dir.string(), ".json");
    EXPECT_FALSE(d.confirm()) << "a directory is not a file";
    d.input() = (dir / "missing.json").string();
    EXPECT_FALSE(d.confirm());
    d.input() = (dir / "project.json").string();
    EXPECT_TRUE(d.confirm());
    EXPECT_EQ(fs::path(d.result()), dir / "project.json");

    d.open(FileDialog::Mode::Save, "Save", (dir / "new").string(), ".json");
    EXPECT_TRUE(d.confirm());
    EXPECT_EQ(fs::path(d.result()), dir / "new.json") << "Save adds the extension";
    d.input() = (dir / "nodir" / "x.json").string();
    EXPECT_FALSE(d.confirm());
    fs::remove_all(dir);
}

TEST(ViewModel, ErrorMetricsAndHighlight) {
    // core's per-pixel metric, compared image (1.5) first, ground truth (1.0) second.
    EXPECT_FLOAT_EQ(pixelError(Vec3(1.5f), Vec3(1.f), ErrorMapKind::Absolute), 0.5f);
    EXPECT_NEAR(pixelError(Vec3(1.5f), Vec3(1.f), ErrorMapKind::Relative), 0.5f / 1.01f, 1e-6f);
    EXPECT_FLOAT_EQ(pixelError(Vec3(1.5f), Vec3(1.f), ErrorMapKind::Squared), 0.25f);

    WorkbenchState s;
    s.groundTruth.global = Image(2, 1, Vec3(0.5f));
    s.groundTruth.revision = 1;
    s.compare.global = Image(2, 1, Vec3(0.75f));
    s.compare.revision = 1;
    s.view.compareSource = CompareSource::Run;  // the compared run, not the (empty) prediction
    s.objectIds = {3, 4};
    s.idWidth = 2;
    s.idHeight = 1;
    s.view.metric = ErrorMapKind::Absolute;
    ViewModel vm;
    vm.update(s);
    ASSERT_EQ(vm.error().width, 2);
    EXPECT_NEAR(vm.error().at(0, 0).x, 0.25f, 1e-6f);
    const auto& ref = vm.image(ViewModel::kReference);
    ASSERT_EQ(ref.rgba.size(), 8u);
    EXPECT_EQ(ref.rgba[0], ref.rgba[4]);
    const uint64_t rev = ref.revision;
    vm.update(s);
    EXPECT_EQ(vm.image(ViewModel::kReference).revision, rev) << "unchanged inputs are not recomputed";
    s.view.selectedObject = 4;
    vm.update(s);
    EXPECT_LT(vm.image(ViewModel::kReference).rgba[0], vm.image(ViewModel::kReference).rgba[4])
        << "pixels of other objects are dimmed";
    s.view.exposure = 1.f;
    vm.update(s);
    EXPECT_EQ(vm.image(ViewModel::kReference).rgba[4], 255) << "0.5 at +1 EV is white";
}

TEST(ViewModel, ErrorMapIsTheMetricRrfEvaluateReports) {
    // A coloured pixel, where the luminance error and the per-channel mean differ: the Views error
    // map must hold core's metric (per channel, averaged over R, G, B), as `rrf evaluate`'s
    // error_<kind>_<term> maps and its per-object statistics do.
    const Vec3 truth(0.8f, 0.2f, 0.05f), predicted(0.5f, 0.4f, 0.05f);
    WorkbenchState s;
    s.groundTruth.direct = Image(3, 2, Vec3(0.1f));
    s.groundTruth.direct.set(1, 1, truth);
    s.groundTruth.touch();
    s.prediction.direct = Image(3, 2, Vec3(0.1f));
    s.prediction.direct.set(1, 1, predicted);
    s.prediction.touch();
    s.view.term = Term::Direct;
    ViewModel vm;
    for (ErrorMapKind k : kErrorMapKinds) {
        s.view.metric = k;
        vm.update(s);
        ASSERT_EQ(vm.error().width, 3) << errorMapName(k);
        const float shown = vm.error().at(1, 1).x;
        EXPECT_EQ(shown, errorMap(s.prediction.direct, s.groundTruth.direct, k).at(1, 1).x) << errorMapName(k);
        EXPECT_EQ(shown, pixelError(predicted, truth, k)) << "the hover read-out shows the map's value";
        const float lum = luminance(predicted) - luminance(truth);
        const float lumError = k == ErrorMapKind::Absolute   ? std::fabs(lum)
                               : k == ErrorMapKind::Relative ? std::fabs(lum) / (luminance(truth) + 0.01f)
                                                             : lum * lum;
        EXPECT_GT(std::fabs(shown - lumError), 0.01f) << errorMapName(k) << ": the pixel must tell the definitions apart";
    }
    // The per-object statistics of `rrf evaluate` over this one pixel agree with the map.
    const ErrorStats one = errorStats(s.prediction.direct, s.groundTruth.direct, {uint32_t(1 * 3 + 1)});
    s.view.metric = ErrorMapKind::Absolute;
    vm.update(s);
    EXPECT_NEAR(vm.error().at(1, 1).x, one.mae, 1e-7);
    s.view.metric = ErrorMapKind::Squared;
    vm.update(s);
    EXPECT_NEAR(vm.error().at(1, 1).x, one.rmse * one.rmse, 1e-7);
    EXPECT_NEAR(vm.error().at(1, 1).x, (0.09 + 0.04) / 3.0, 1e-6);
}

}  // namespace rrf::test::test_project_io
