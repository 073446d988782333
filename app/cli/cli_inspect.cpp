// `rrf inspect`: a dataset's header, record counts and per-object statistics of every column; or, for
// a scene or project file (.json), the scene's objects with their materials, its lights and effects.
#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/commands.h"
#include "core/data/dataset_file.h"
#include "core/data/dataset_summary.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "core/scene/effects.h"
#include "core/scene/scene_summary.h"

namespace rrf::cli {

void addInspectCommand(CLI::App& app, int& exitCode) {
    auto file = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand(
        "inspect", "Print a dataset's header, counts and per-object statistics, or a scene's objects, materials and lights");
    cmd->add_option("file", *file, "dataset file, or a scene or project file (.json)")->required();
    cmd->callback([file, &exitCode] {
        if (file->size() >= 5 && file->compare(file->size() - 5, 5, ".json") == 0) {
            const Project p = loadProjectOrScene(*file);
            std::fputs(formatSceneSummary(p.scene).c_str(), stdout);
            std::fputs("effects:\n", stdout);
            const Effects effects = Effects::derive(p.scene);
            for (const std::string& line : effects.describe()) std::printf("  %s\n", line.c_str());
            const EstimatorChoice render = chooseEstimator(p.render.estimator, effects);
            const EstimatorChoice records = chooseEstimator(p.samplingOrDefault().estimator, effects);
            std::printf("estimator: images (render, references) %s: %s\n", estimatorName(render.estimator),
                        render.reason.c_str());
            std::printf("estimator: training records %s: %s\n", estimatorName(records.estimator), records.reason.c_str());
            exitCode = 0;
            return;
        }
        const Dataset data(*file);
        std::fputs(formatDatasetReport(data, summarizeDataset(data)).c_str(), stdout);
        exitCode = 0;
    });
}

}  // namespace rrf::cli
