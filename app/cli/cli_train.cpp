// `rrf train`: one network per object (and target) from a dataset, saved as a model directory. Under
// an MPI launcher the ranks share the objects and rank 0 writes the models (docs/cluster.md).
#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdio>
#include <mutex>
#include <memory>
#include <sstream>
#include <vector>
#include <string>

#include "app/cli/cli_common.h"
#include "app/cli/cli_ranks.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "core/data/dataset_file.h"
#include "core/project/project_file.h"
#include "core/util/error.h"
#include "core/nn/mlp_kernel.h"
#include "core/nn/model_set.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/network_settings.h"
#include "core/project/project.h"
#include "core/pipeline/run_recording.h"
#include "core/pipeline/train_stage.h"
#include "app/cli/cli_stage.h"
#include "app/cli/cli_record.h"
#include "app/mpi/ranks.h"
#include "core/util/stopwatch.h"
#include "core/nn/training_run.h"

namespace rrf::cli {

namespace {
struct TrainArgs {
    std::string input, data, out;
    std::vector<std::string> objects;
    int threads = 0, logEvery = 10;
    bool record = false;
    SettingFlags<ObjectTrainingOptions> network;  ///< --hidden, --encoding, --trainer, --epochs, --targets
};

/// "--objects 0,3,tall-box": ids or names of scene objects.
std::vector<int> objectIds(const std::vector<std::string>& names, const Scene& scene) {
    std::vector<int> ids;
    for (const std::string& part : names) {
        int found = -1;
        for (const Object& o : scene.objects)
            if (o.name == part || std::to_string(o.id) == part) found = o.id;
        if (found < 0) {
            std::string known;
            for (const Object& o : scene.objects) known += (known.empty() ? "" : ", ") + std::to_string(o.id) + "=" + o.name;
            throw InputError("command line", "--objects", "no object '" + part + "' (known: " + known + ")");
        }
        ids.push_back(found);
    }
    return ids;
}

std::string fmt(double v) {
    if (std::isnan(v)) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

int runTrain(const TrainArgs& a, std::optional<Run> record) {
    const mpi::Ranks& ranks = mpi::ranks();
    const Project project = loadProjectOrScene(a.input);
    std::vector<std::string> inputs = projectInputs(project);
    inputs.push_back(a.data);
    refuseOverwritingInputs(a.out, inputs);
    ObjectTrainingOptions o = project.trainingOptions();
    a.network.applyTo(o);
    if (!a.objects.empty()) o.objects = objectIds(a.objects, project.scene);
    auto threads = limitThreads(a.threads);

    const Dataset data(a.data, true, project.scene.contentHash());
    const int datasetInputs = data.inputCount();
    const std::string encoding = networkEncoding(o.encoding, datasetInputs, o.inputs).describe();
    if (ranks.isRoot()) {
        std::printf("rrf train: %s on %s (%llu records), hidden %s, %s%s, encoding %s, targets %s, trainer %s, kernel %s\n",
                a.input.c_str(), a.data.c_str(), (unsigned long long)data.totalRecords(),
                hiddenSizesText(o.hidden).c_str(),
                activationName(o.activation), o.ensemble > 1 ? (", ensemble of " + std::to_string(o.ensemble)).c_str() : "",
                encoding.c_str(), targetModeName(o.targets), o.trainer.typeName(),
                mlpKernelDescription(mlpKernel()).c_str());
        // Objects whose "network"/"objects" entry changes their networks say so (nn/object_network_overrides.h).
        for (const auto& entry : o.perObject) {
            const ObjectNetworkChoice c = o.choiceFor(entry.first);
            std::printf("  object %s: hidden %s, encoding %s\n", entry.first.c_str(), hiddenSizesText(c.hidden).c_str(),
                        networkEncoding(c.encoding, datasetInputs, c.inputs).describe().c_str());
        }
    }
    std::fflush(stdout);

    std::mutex printMutex;
    StageObserver observer;
    observer.epoch = [&](int id, const std::string& target, const EpochRecord& r) {
        if (a.logEvery <= 0 || r.epoch % a.logEvery != 0) return;
        std::lock_guard<std::mutex> lock(printMutex);
        std::printf("object %d %-10s %-8s epoch %4d  train %-10s validation %-10s step %-9s %7.2f s\n", id,
                    project.scene.objects[size_t(id)].name.c_str(), target.c_str(), r.epoch, fmt(r.trainLoss).c_str(),
                    fmt(r.validationLoss).c_str(), fmt(r.step).c_str(), r.seconds);
        std::fflush(stdout);
    };
    observer.message = [&](const std::string& m) {
        std::lock_guard<std::mutex> lock(printMutex);
        std::printf("note: %s\n", m.c_str());
        std::fflush(stdout);
    };
    TrainRequest request;
    request.options = o;
    request.sampling = project.sampling;
    request.sceneHash = project.scene.contentHash();
    request.modelsDir = a.out;
    request.provenance = {a.data, a.input};
    std::optional<RankTraining> rankTraining;
    request.share = rankTrainingOrNull(rankTraining, ranks, project.scene);
    const double cpuStart = processCpuSeconds();
    TrainOutcome outcome;
    runStage("train", [&](const StageObserver& obs) { outcome = trainFromDataset(data, request, obs); }, observer);
    const TrainingRun& run = outcome.run;
    if (!ranks.isRoot()) return run.cancelled ? 130 : 0;
    const std::vector<ObjectModel>& trained = run.models;
    const double seconds = run.seconds;

    // "valid rel" is the figure the error goal and the kd-tree's splits are stated in (noise-corrected
    // validation relative RMSE where the targets' noise is known); "stop" says why each network ended.
    std::printf("\n%-4s %-12s %-9s %9s %7s %7s %-11s %-11s %-11s %-10s %8s  %s\n", "id", "object", "target", "samples",
                "params", "epochs", "train RMSE", "valid RMSE", "test RMSE", "valid rel", "time s", "stop");
    for (const ObjectModel& m : trained) {
        if (m.skipped) {
            std::printf("%-4d %-12s %-9s skipped: %s\n", m.objectId, m.objectName.c_str(), m.target.c_str(), m.message.c_str());
            continue;
        }
        // One row per network: a partitioned model's leaves are listed as target#leaf.
        for (int l = 0; l < m.model.leafCount(); ++l) {
            const NetworkModel& net = m.model.leaves[size_t(l)];
            const TrainResult& t = net.training;
            const std::string target = m.model.leafCount() == 1 ? m.target : m.target + "#" + std::to_string(l);
            const double rel = t.judgedValidationError();
            std::printf("%-4d %-12s %-9s %9lld %7lld %7d %-11s %-11s %-11s %-10s %8.2f  %s\n", m.objectId, m.objectName.c_str(),
                        target.c_str(), (long long)(t.trainSamples + t.validationSamples + t.testSamples),
                        (long long)net.numParams(), t.epochs, fmt(net.errors.train).c_str(),
                        fmt(net.errors.validation).c_str(), fmt(net.errors.test).c_str(), fmt(rel).c_str(), t.seconds,
                        t.stopReason.c_str());
        }
    }
    std::printf("trained in %.2f s (%.2f s CPU%s)%s; wrote %s/models.json\n", seconds, processCpuSeconds() - cpuStart,
                ranks.size() > 1 ? " of rank 0" : "", run.cancelled ? " (stopped early by Ctrl-C)" : "", a.out.c_str());
    if (record && run.networks > 0) {
        setTrainRun(*record, projectDirectory(project), std::move(outcome.record));
        finishRecording(a.input, *record);
    } else if (record) {
        std::printf("no network was trained; no run recorded\n");
    }
    return run.cancelled ? 130 : 0;
}
}  // namespace

void addTrainCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<TrainArgs>();
    CLI::App* cmd = app.add_subcommand("train", "Train one network per object (and target) on a dataset");
    cmd->add_option("input", a->input, "project or scene JSON file")->required();
    cmd->add_option("--data", a->data, "dataset file (.rrfd) made for this scene")->required();
    cmd->add_option("--out", a->out, "output model directory (required unless --record)");
    addNetworkFlags(cmd, a->network);
    cmd->add_option("--objects", a->objects, "objects to train (ids or names, comma-separated)")
        ->delimiter(',')
        ->allow_extra_args(false)
        ->type_name("ID|NAME[,...]");
    a->network
        .add<std::string>(cmd, "--targets", "what the networks predict",
                          [](ObjectTrainingOptions& t, const std::string& m) { t.targets = parseTargetMode(m); })
        ->check(CLI::IsMember({"separate", "joint", "global", "direct", "indirect"}));
    cmd->add_option("--threads", a->threads, "worker threads (0 = all cores)")->check(nonNegative());
    cmd->add_option("--log-every", a->logEvery, "print every N-th epoch (0 = none)")->check(nonNegative());
    cmd->add_flag("--record", a->record, recordHelp("a train run (models under runs/<id>/models)"));
    cmd->callback([a, &exitCode] {
        // In an MPI job rank 0 alone writes the models and records the run; the others need no --out.
        std::optional<Run> record;
        if (mpi::ranks().isRoot()) record = beginRecording(a->record, a->input, "train", a->out, "models");
        exitCode = runTrain(*a, std::move(record));
    });
}

}  // namespace rrf::cli
