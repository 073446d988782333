// bench_save: saving a model set (core/nn/model_set.h) as the workbench does after a training, and
// the same files written the way sets were saved before issue 29 (each file its own AtomicFile:
// temporary, fsync, rename, fsync of the directory) for comparison, on the file system of --dir:
//
//   bench_save [--files 120] [--hidden 40,10] [--reps 3] [--dir /tmp]
//
// One network per file (objects × one leaf each, 16 inputs, 3 outputs): a kd-tree set of many
// leaves writes as many files. Prints bytes, files and the fastest of --reps seconds for each way.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "bench/bench_args.h"
#include "core/nn/model.h"
#include "core/nn/model_set.h"
#include "core/util/atomic_file.h"

using namespace rrf;

namespace bench_save {

namespace fs = std::filesystem;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

/// A network of the given hidden sizes with small made-up weights (what is saved, not what it predicts).
ObjectModel model(int id, const std::vector<int>& hidden) {
    NetworkModel net;
    net.arch.inputs = 16;
    net.arch.hidden = hidden;
    net.arch.outputs = 3;
    net.params = VecX<double>::Random(net.arch.numParams()) * 0.1;
    net.inputScaler = MinMaxScaler::identity(16);
    net.outputScaler = MinMaxScaler::identity(3);
    net.objectId = id;
    net.objectName = "object " + std::to_string(id);
    ObjectModel m;
    m.objectId = id;
    m.objectName = net.objectName;
    m.target = net.target;
    m.model = PartitionedNetwork(std::move(net));
    return m;
}

int main(int argc, char** argv) {
    int files = 120, reps = 3;
    std::vector<int> hidden{40, 10};
    std::string base = fs::temp_directory_path().string();
    CLI::App app{"saving a model set: one staged set against per-file atomic writes", "bench_save"};
    app.add_option("--files", files, "network files in the set")->check(bench::kPositive);
    app.add_option("--hidden", hidden, "hidden layer sizes")->delimiter(',');
    app.add_option("--reps", reps, "repetitions (the fastest is shown)")->check(bench::kPositive);
    app.add_option("--dir", base, "where the sets are written (its file system is what is measured)");
    bench::parseArgs(app, argc, argv);
    std::vector<ObjectModel> set;
    for (int i = 0; i < files; ++i) set.push_back(model(i, hidden));
    std::vector<std::string> layout(16, "x");
    const fs::path root = fs::path(base) / ("bench_save." + std::to_string(::getpid()));
    fs::create_directories(root);
    double staged = 1e30, perFile = 1e30;
    size_t bytes = 0;
    for (int r = 0; r < reps; ++r) {
        double t = now();
        saveModelSet((root / "set").string(), set, 0x1234, layout);
        staged = std::min(staged, now() - t);
        // Before: every file through AtomicFile into the set's directory, then read back for its checksum.
        const fs::path old = root / ("old" + std::to_string(r));
        fs::create_directories(old);
        t = now();
        bytes = 0;
        for (const ObjectModel& m : set) {
            const std::string path = (old / ("object_" + std::to_string(m.objectId) + ".rrfm")).string();
            writeFileAtomically(path, modelFileBytes(m.model.leaves[0]));
            bytes += readFile(path).size();
        }
        perFile = std::min(perFile, now() - t);
    }
    std::error_code ec;
    fs::remove_all(root, ec);
    std::printf("bench_save: %d files of %s, %.1f KiB, in %s, fastest of %d\n", files, set[0].model.arch().describe().c_str(),
                double(bytes) / 1024.0, base.c_str(), reps);
    std::printf("| way | seconds |\n|---|---|\n| saveModelSet (staged, synced together) | %.3f |\n| per-file atomic writes (before) | %.3f |\n",
                staged, perFile);
    return 0;
}

}  // namespace bench_save
