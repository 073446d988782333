#pragma once
/// The data stage: training records of a scene (core/data/data_generator.h), written whole as one
/// dataset file. `rrf generate`, `rrf pipeline` and the workbench's Generate job run it; sweeps that
/// vary the sampling call the generator per point and keep the records in memory.

#include <functional>
#include <string>

#include "core/data/data_generator.h"
#include "core/pipeline/stage_observer.h"

namespace rrf {

/// Makes the records with `generator` some other way than all in this process (a shard, the CLI's
/// MPI ranks): returns the joined records on the process that writes them, and may return empty
/// data elsewhere.
using GenerateFunction = std::function<GeneratedData(const DataGenerator& generator)>;

struct GenerateRequest {
    std::string datasetPath;     ///< where the dataset goes; empty: kept in memory only
    GenerateFunction generate;   ///< empty: every cell in this process, with progress and cancel
    bool writes = true;          ///< false on processes that make records but do not write the file
};

struct GenerateOutcome {
    GeneratedData data;          ///< records, header and what the generator did (data.cancelled: stopped)
    bool written = false;        ///< the dataset file was (re)placed whole at the request's path
};

/// Generates the records of `generator` (a scene and its sampling settings) as `request` says and writes them to its dataset path unless the
/// run was cancelled (then nothing is written: the old file, if any, stays as it was). Throws what
/// DataGenerator throws (a grid that does not fit in memory, a scene whose every sample is NaN).
GenerateOutcome generateStage(const DataGenerator& generator, const GenerateRequest& request, const StageObserver& observer);

}  // namespace rrf
