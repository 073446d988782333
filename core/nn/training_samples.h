#pragma once
/// Bridge from a dataset file to the trainer's in-memory samples.

#include <string>
#include <vector>

#include "core/data/dataset_file.h"
#include "core/nn/object_training.h"

namespace rrf {

/// One ObjectSamples per dataset object (copies of the mapped records: inputs, direct, indirect).
/// Records with a non-finite value are dropped and counted in `dropped` (the generator never writes
/// them, so a non-zero count means the file was produced by something else).
std::vector<ObjectSamples> samplesFromDataset(const Dataset& data, uint64_t* dropped = nullptr);

/// The samples of one object from `count` records laid out as the generator writes them
/// (`inputs` floats, then direct RGB and indirect RGB). Records with a non-finite value are left
/// out and added to `dropped`. Used for dataset files and for in-memory generator output alike.
ObjectSamples objectSamples(int objectId, const std::string& name, const float* records, size_t count, int inputs,
                            uint64_t& dropped);

}  // namespace rrf
