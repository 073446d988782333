#pragma once
/// The stages that split their work across the ranks of an MPI job (docs/cluster.md), one definition
/// each for the commands that run them: data generation (`rrf generate`, `rrf pipeline`, the shared
/// dataset of `rrf sweep`), training (`rrf train`, `rrf pipeline`) and stored references (`rrf
/// evaluate`, `rrf pipeline`). With one rank each runs as one process does. Every function here is
/// collective: all ranks call it, in the same order.

#include <atomic>
#include <optional>
#include <vector>

#include "app/mpi/ranks.h"
#include "app/cli/cli_evaluation.h"
#include "core/data/data_generator.h"
#include "core/nn/training_run.h"
#include "core/pipeline/train_stage.h"
#include "core/util/stopwatch.h"

namespace rrf::cli {

/// Generates `gen`'s data with a progress line: shard k of n in one process; in an MPI job of more
/// than one rank (n must be 1) each rank its contiguous range of cells balanced by predicted records
/// (core/data/cell_split.h; rank 0 predicts and sends the costs), logged, and rank 0 joins the parts
/// into the single-process run's data (core/data/dataset_part.h). Returns that data on rank 0 and an
/// empty one on the others. A rank interrupted by Ctrl-C stops the job (stopJobOnError(130)); in
/// one process the data comes back with `cancelled` set.
GeneratedData generateOnRanks(const DataGenerator& gen, const mpi::Ranks& ranks, int shardK = 0, int shardN = 1);

/// generateOnRanks, then rank 0 sends the joined data to every rank (core/data/dataset_part.h): the
/// whole data on every rank, for stages after it that every rank runs on all of it.
GeneratedData generateOnAllRanks(const DataGenerator& gen, const mpi::Ranks& ranks);

/// Renders the reference of `scene` with the light at `lp` (as renderWithProgress, with a progress
/// line labelled `label`): in an MPI job each rank the rows y with y mod N = its rank, logged, and
/// rank 0 joins them into the single-process render, bit for bit (core/render/render_rows.h).
/// Returns the reference on rank 0 and an empty one on the others. Ctrl-C stops the job.
Reference renderOnRanks(const Scene& scene, const Vec3& lp, const RenderOptions& options, const std::string& label,
                        const mpi::Ranks& ranks);

/// The ranks' share of a training (core/pipeline/train_stage.h): in an MPI job each rank trains its
/// objects, assigned longest first by record count (core/nn/training_split.h) and logged, and rank 0
/// joins the parts into the single-process run, weights bit for bit (core/nn/training_part.h), its
/// seconds the wall time from the start to the joined run. join returns the whole run on rank 0, the
/// rank's own part on the others; rank 0 alone saves.
class RankTraining : public TrainingShare {
public:
    RankTraining(const mpi::Ranks& ranks, const Scene& scene) : ranks_(ranks), scene_(scene) {}
    ObjectTrainingOptions mine(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options) override;
    TrainingRun join(TrainingRun run, const ObjectTrainingOptions& options) override;
    bool saves() const override { return ranks_.isRoot(); }

private:
    const mpi::Ranks& ranks_;
    const Scene& scene_;
    std::vector<int> rankOfPosition_;
    Stopwatch clock_;
    double cpuStart_ = 0;
};

/// The share of a training for this process: a RankTraining in an MPI job of more than one rank,
/// else none (null: one process trains everything).
TrainingShare* rankTrainingOrNull(std::optional<RankTraining>& storage, const mpi::Ranks& ranks, const Scene& scene);

/// In an MPI job of more than one rank: this rank renders (or continues) the references of its share
/// of `lights` into the project's store — light k to rank k mod N (longest first on equal costs),
/// each rank one reference at a time with all its threads — and all ranks wait for the last.
/// Rank 0 then evaluates as one process does and finds every reference in the store. The store's
/// entries are directories written whole, one per light, so ranks never write the same file; the
/// project's directory must be shared by the ranks (docs/cluster.md).
void obtainRankReferences(const mpi::Ranks& ranks, const std::vector<Vec3>& lights, const ReferenceSource& source);

}  // namespace rrf::cli
