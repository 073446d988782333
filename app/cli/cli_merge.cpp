// `rrf merge`: dataset shards (`rrf generate --shard k/n`) into one file, byte-identical to the
// unsharded run.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/data/dataset_file.h"

namespace rrf::cli {

void addMergeCommand(CLI::App& app, int& exitCode) {
    auto inputs = std::make_shared<std::vector<std::string>>();
    auto out = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("merge", "Merge dataset shards into one file");
    cmd->add_option("inputs", *inputs, "shard files")->required();
    cmd->add_option("--out", *out, "merged dataset file")->required();
    cmd->callback([inputs, out, &exitCode] {
        refuseOverwritingInputs(*out, *inputs);
        mergeDatasets(*inputs, *out);
        std::printf("merged %zu shards into %s\n", inputs->size(), out->c_str());
        exitCode = 0;
    });
}

}  // namespace rrf::cli
