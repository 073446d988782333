#include "app/cli/cli_record.h"

#include <cstdio>
#include <filesystem>

#include "core/project/project.h"
#include "core/pipeline/run_recording.h"
#include "core/project/project_file.h"
#include "core/util/error.h"

namespace rrf::cli {

std::string recordHelp(const std::string& what) {
    return "record " + what + " in the project's runs, as the workbench does (files under <project dir>/runs/<id>/ "
           "unless --out); this saves the project file, which the CLI otherwise never changes";
}

std::optional<Run> beginRecording(bool record, const std::string& input, const std::string& kind, std::string& out,
                                  const std::string& sub) {
    if (!record) {
        if (out.empty()) throw InputError("command line", "--out", "an output directory is required (or --record)");
        return std::nullopt;
    }
    const Project project = loadProjectOrScene(input);
    if (isBareScene(project))
        throw InputError("command line", "--record",
                         input + " is a scene file, not a project: there is no project to record the run in");
    Run run = beginRun(project.runs, kind);
    if (out.empty()) {
        const std::filesystem::path dir = runDirectory(projectDirectory(project), run);
        out = (sub.empty() ? dir : dir / sub).string();
    }
    return run;
}

void finishRecording(const std::string& input, const Run& run) {
    recordRun(input, run);
    std::printf("recorded %s run '%s' in %s\n", run.kind.c_str(), run.id.c_str(), input.c_str());
}

}  // namespace rrf::cli
