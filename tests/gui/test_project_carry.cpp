// Save As carries a project's runs, references and dataset to the new directory (issue 14 item 3):
// after saving elsewhere and re-opening from there, every run's files resolve, artifacts outside
// the project are relinked to the same file, and the old directory is left as it was.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/project/project_files.h"
#include "core/pipeline/run_recording.h"
#include "panels/project_io.h"

namespace rrf::test::test_project_carry {

namespace fs = std::filesystem;
using namespace rrf::panels;

namespace {
const fs::path kCornellDir = RRF_SOURCE_DIR "/projects/cornell-box";

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("rrf_gui_carry_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeText(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
}

std::string readText(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
}  // namespace

TEST(ProjectCarry, SaveAsBringsRunsReferencesAndDatasetAlong) {
    const fs::path root = scratch("saveas");
    const fs::path a = root / "a", b = root / "elsewhere" / "b";
    fs::create_directories(a);
    fs::copy_file(kCornellDir / "project.json", a / "project.json");
    fs::copy_file(kCornellDir / "scene.json", a / "scene.json");
    // A training run's model directory (two files, only models.json is listed as the artifact),
    // a render run's image, a reference of the store, the dataset, and a report outside the project.
    writeText(a / "runs/train-1/models/models.json", "{\"index\": 1}");
    writeText(a / "runs/train-1/models/object0_indirect.rrfm", "weights");
    writeText(a / "runs/render-1/global.exr", "pixels");
    writeText(a / "references/ref-1/reference.json", "{}");
    writeText(a / "data/dataset.rrfd", "records");
    writeText(root / "shared/report.json", "report");

    WorkbenchState s;
    std::string error;
    ASSERT_TRUE(loadProjectIntoState(s, (a / "project.json").string(), error)) << error;
    rrf::Run train;
    train.id = train.name = "train-1";
    train.kind = "train";
    train.settings.dataset = "data/dataset.rrfd";
    train.artifacts = {"runs/train-1/models/models.json", "../shared/report.json"};
    rrf::Run render;
    render.id = render.name = "render-1";
    render.kind = "render";
    render.artifacts = {"runs/render-1/global.exr"};
    s.project.runs = {train, render};
    s.dataset.path = (a / "data/dataset.rrfd").string();

    fs::create_directories(b);
    ASSERT_TRUE(saveStateToProject(s, (b / "project.json").string(), error)) << error;

    // Re-opened from the new place, the runs' files are there.
    WorkbenchState t;
    ASSERT_TRUE(loadProjectIntoState(t, (b / "project.json").string(), error)) << error;
    ASSERT_EQ(t.project.runs.size(), 2u);
    const std::string models = trainRunModelsDir(t.project.runs[0], projectDirectory(t.project));
    EXPECT_EQ(fs::path(models).lexically_normal(), (b / "runs/train-1/models").lexically_normal());
    EXPECT_EQ(readText(b / "runs/train-1/models/models.json"), "{\"index\": 1}");
    EXPECT_EQ(readText(b / "runs/train-1/models/object0_indirect.rrfm"), "weights") << "unlisted model files travel too";
    EXPECT_EQ(readText(b / "runs/render-1/global.exr"), "pixels");
    EXPECT_EQ(readText(b / "references/ref-1/reference.json"), "{}");
    EXPECT_EQ(readText(b / "data/dataset.rrfd"), "records");
    // The report outside the project is relinked: from b it names the same file.
    ASSERT_EQ(t.project.runs[0].artifacts.size(), 2u);
    EXPECT_EQ(t.project.runs[0].artifacts[1], "../../shared/report.json");
    EXPECT_EQ(readText(b / t.project.runs[0].artifacts[1]), "report");
    // This session's dataset follows; the old project is untouched.
    EXPECT_EQ(fs::path(s.dataset.path).lexically_normal(), (b / "data/dataset.rrfd").lexically_normal());
    EXPECT_EQ(readText(a / "runs/train-1/models/models.json"), "{\"index\": 1}");
    WorkbenchState old;
    ASSERT_TRUE(loadProjectIntoState(old, (a / "project.json").string(), error)) << error;
    EXPECT_TRUE(old.project.runs.empty()) << "Save As must not write into the old project file";
    fs::remove_all(root);
}

TEST(ProjectCarry, SavingInPlaceCarriesNothing) {
    const fs::path dir = scratch("inplace");
    writeText(dir / "runs/r/models/models.json", "x");
    std::vector<rrf::Run> runs(1);
    runs[0].id = "r";
    runs[0].kind = "train";
    runs[0].artifacts = {"runs/r/models/models.json", "../outside.json"};
    const CarriedFiles c = carryProjectFiles(dir.string(), (dir / ".").string(), runs);
    EXPECT_EQ(c.linked + c.copied + c.relinked, 0);
    EXPECT_EQ(runs[0].artifacts[1], "../outside.json") << "a path is relinked only when the directory changes";
    fs::remove_all(dir);
}

TEST(ProjectCarry, AFileAlreadyAtTheDestinationIsKept) {
    const fs::path root = scratch("existing");
    writeText(root / "a/runs/r/models/models.json", "new");
    writeText(root / "b/runs/r/models/models.json", "user's own");
    std::vector<rrf::Run> runs(1);
    runs[0].id = "r";
    runs[0].kind = "train";
    const CarriedFiles c = carryProjectFiles((root / "a").string(), (root / "b").string(), runs);
    EXPECT_EQ(c.linked + c.copied, 0);
    EXPECT_EQ(readText(root / "b/runs/r/models/models.json"), "user's own");
    fs::remove_all(root);
}

}  // namespace rrf::test::test_project_carry
