#pragma once
/// In-memory glue between the stages, for runs that never touch the disk between them (the pipeline
/// command, sweeps, end-to-end tests): generated records → training samples → trained networks →
/// a ModelSet the predictor takes. Training itself is trainNetworks (core/nn/training_run.h), as in
/// the file-based path (rrf generate / train / evaluate), which gives the same networks from the
/// same settings.

#include <vector>

#include "core/data/data_generator.h"
#include "core/nn/model_set.h"
#include "core/nn/object_training.h"

namespace rrf {

/// One ObjectSamples per scene object from the generator's records (layout: `layout`).
std::vector<ObjectSamples> samplesFromGenerated(const GeneratedData& data, const Scene& scene, const RecordLayout& layout);

/// A ModelSet holding the non-skipped networks of `trained` (no files), ready for Predictor.
ModelSet modelSetFromTrained(const std::vector<ObjectModel>& trained, const Scene& scene, const RecordLayout& layout);

}  // namespace rrf
