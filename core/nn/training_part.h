#pragma once
/// The ranks' shares of one training run (core/nn/training_split.h), sent to rank 0 as bytes and
/// joined into the run one process makes: the same models in the same order, weights and training
/// records bit for bit, the same loss curves. Only the wall times differ, as they do between two
/// runs of one process.

#include <string>
#include <vector>

#include "core/nn/training_run.h"

namespace rrf {

/// The bytes of `run` for another process of the same build (core/util/byte_stream.h): every model
/// (each leaf as its model file's bytes, nn/model.h, plus the training record fields a model file
/// does not keep), the kd-trees, the curves, seconds and the cancel flag.
std::string encodeTrainingPart(const TrainingRun& run);

/// Reads what encodeTrainingPart wrote; `source` (e.g. "rank 2") names the part in errors. Throws
/// std::runtime_error on a truncated transfer and InputError on a malformed model.
TrainingRun decodeTrainingPart(const std::string& bytes, const std::string& source);

/// Joins the parts of a run whose objects were assigned to ranks: `rankOfPosition[p]` is the rank
/// that trained the p-th object of trainObjects' order and `parts[r]` what rank r returned (its
/// objects in that order, `networksPerObject` entries each). The models come out in trainObjects'
/// order, the curves ordered by (object id, target) as trainNetworks orders them; `seconds` is the
/// longest part's, `cancelled` whether any part was. Throws std::runtime_error when a part holds
/// fewer or more entries than its positions need.
TrainingRun joinTrainingParts(std::vector<TrainingRun> parts, const std::vector<int>& rankOfPosition,
                              int networksPerObject);

}  // namespace rrf
