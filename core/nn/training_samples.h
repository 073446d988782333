#pragma once
/// Bridge from a dataset file to the trainer's in-memory samples.

#include <string>
#include <vector>

#include "core/data/dataset_file.h"
#include "core/nn/object_training.h"

namespace rrf {

/// One ObjectSamples per dataset object (copies of the mapped records: inputs, direct, indirect and,
/// when the file stores them, the targets' variances). Records with a non-finite value are dropped
/// and counted in `dropped` (the generator never writes them, so a non-zero count means the file
/// was produced by something else). Throws std::runtime_error naming the file when the record
/// layout is not inputs, 6 targets and optionally the 6 noise columns of RecordLayout::noiseNames().
std::vector<ObjectSamples> samplesFromDataset(const Dataset& data, uint64_t* dropped = nullptr);

/// The samples of one object from `count` records laid out as the generator writes them
/// (`inputs` floats, direct RGB, indirect RGB, then — when `withNoise` — the variances of the six
/// target means). Records with a non-finite value are left out and added to `dropped`. An object
/// with a record whose variance is unknown (negative: fewer than two path samples) gets no
/// variances at all (its noise is unknown). Used for dataset files and for in-memory generator
/// output alike.
ObjectSamples objectSamples(int objectId, const std::string& name, const float* records, size_t count, int inputs,
                            bool withNoise, uint64_t& dropped);

}  // namespace rrf
