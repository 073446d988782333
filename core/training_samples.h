#pragma once
/// Bridge from a dataset file to the trainer's in-memory samples.

#include <vector>

#include "core/dataset_file.h"
#include "core/nn_objects.h"

namespace rrf {

/// One ObjectSamples per dataset object (copies of the mapped records: inputs, direct, indirect).
/// Records with a non-finite value are dropped and counted in `dropped` (the generator never writes
/// them, so a non-zero count means the file was produced by something else).
std::vector<ObjectSamples> samplesFromDataset(const Dataset& data, uint64_t* dropped = nullptr);

}  // namespace rrf
