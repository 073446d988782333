#pragma once
/// The dataset header (core/data/dataset_file.h's JSON header) of a generator run: built from the
/// typed fields of GeneratedData (core/data/data_generator.h) and read back into them, for the
/// dataset writer, the parts sent between processes (core/data/dataset_part.h) and merges.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "core/data/data_generator.h"
#include "core/util/json_text.h"

namespace rrf {

/// The header's descriptive keys of a run (GeneratedData::description): "format", "scene_hash",
/// "settings", "light_region", "grid_bounds", "effects", "estimator" (used, reason) and "objects"
/// (each object's id and name, in Scene::objects order).
JsonText datasetDescription(const Scene& scene, uint64_t sceneHash, const SamplingSettings& settings,
                            const Bounds3& lightRegion, const Bounds3& gridBounds, const Effects& effects,
                            const EstimatorChoice& estimator);

/// The header of `data`: its description with the record layout, "floats_per_record", "shard" and
/// "stats" (what writeDataset stores; it fills in the objects' counts and offsets).
nlohmann::json datasetHeader(const GeneratedData& data);

/// Reads a header (a dataset file's, or a part's from encodeGeneratedPart) into `data`'s header
/// fields: description (the objects without counts and offsets), layout, shard and stats
/// (generatorStatsFromHeader). `file` names it in errors; a missing or mistyped field is an
/// InputError naming its JSON pointer. Returns the number of objects the header lists.
size_t readDatasetHeader(const nlohmann::json& header, const std::string& file, GeneratedData& data);

}  // namespace rrf
