// `rrf inspect`: a dataset's header, record counts and per-object statistics of every column.
#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/commands.h"
#include "core/data/dataset_file.h"
#include "core/data/dataset_summary.h"

namespace rrf::cli {

void addInspectCommand(CLI::App& app, int& exitCode) {
    auto file = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("inspect", "Print a dataset's header, counts and per-object statistics");
    cmd->add_option("dataset", *file, "dataset file")->required();
    cmd->callback([file, &exitCode] {
        const Dataset data(*file);
        std::fputs(formatDatasetReport(data, summarizeDataset(data)).c_str(), stdout);
        exitCode = 0;
    });
}

}  // namespace rrf::cli
