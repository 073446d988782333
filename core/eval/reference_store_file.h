#pragma once
/// The reference store's files (core/eval/reference_store.h): an entry's reference.json (its key,
/// spp, noise and state) and render.json (what `rrf render` writes beside its images, so an entry
/// loads like any reference), and the key's JSON, which stored ground truths and evaluations share.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "core/eval/reference_store.h"

namespace rrf {

/// The name of an entry's description in its directory.
constexpr const char* kReferenceEntryFile = "reference.json";

/// {"scene_hash", "camera_hash" (16 hex digits), "light_position", "width", "height", "estimator"
/// ("nee"|"naive"|"bdpt": the estimator that ran, never "auto"), "max_depth", "seed"}.
nlohmann::json toJson(const ReferenceKey& k);
/// The key written by toJson(); throws InputError naming `file` and the pointer below `pointer`.
ReferenceKey referenceKeyFromJson(const nlohmann::json& j, const std::string& file, const std::string& pointer);

/// Reads the reference.json of the entry in `dir`; throws InputError naming it when it is not one the
/// store wrote or its key's id is not the directory's name.
StoredReference readReferenceEntry(const std::string& dir);

/// What an entry's reference.json records beside its key and noise.
struct ReferenceEntryFigures {
    int spp = 0;
    double seconds = 0;
    uint64_t nonFinite = 0;
    bool complete = false;
    double wantedNoise = 0;  ///< NaN: unknown (written as null)
};

/// Writes render.json (core/eval/reference_file.h, with the variance images of `ref` when it has
/// them) and reference.json into the entry directory `dir` being assembled; `stateFile` and `stateChecksum` name the render state
/// written beside them. Throws std::runtime_error when a file cannot be written.
void writeReferenceEntryFiles(const std::string& dir, const ReferenceKey& key, const Reference& ref,
                              const ReferenceNoise& noise, const ReferenceEntryFigures& figures,
                              const std::string& stateFile, const std::string& stateChecksum);

}  // namespace rrf
