#pragma once
/// The encoding types by name, as tiny-cuda-nn's "otype" registry (docs/design.md §10a): each type's
/// name, its hyperparameter keys, the most inputs one component may read, its component id in the
/// GLSL predictor's network texture, and its factory, in
/// one row kept beside its implementation (FrequencyEncoding::type() in encodings/frequency.cpp, …);
/// the JSON of its hyperparameters is read and written by encodings/encodings_json.h.
/// The "encoding" codec (nn/encoding_settings_json.h), the builder of a network's encoding
/// (nn/encoding_settings.h), the model file and the network texture look types up here, so a type's
/// name is spelled once and a new encoding is one implementation, one entry of encodingTypes(),
/// one alternative of EncodingParams (encodings/encoding_params.h), at the same position, and its
/// reader and writer in encodings/encodings_json.cpp.

#include <memory>
#include <string>
#include <vector>

#include "core/nn/encoding.h"
#include "core/nn/encodings/encoding_params.h"

namespace rrf {

/// One encoding type.
struct EncodingType {
    const char* name;               ///< the component's "type" in JSON and Encoding::typeName()
    std::vector<std::string> keys;  ///< its hyperparameter keys (a component also has "type" and "inputs")
    int maxInputs;                  ///< most inputs one component of this type reads
    int glslId;                     ///< component type in the network texture (shaders/encoding.glsl)
    /// The encoding of `params` (this type's alternative) over `inputDims` inputs; throws
    /// std::invalid_argument (naming the setting) for a combination out of range (e.g. a hash grid's
    /// finest resolution or table size).
    std::shared_ptr<const Encoding> (*make)(const EncodingParams& params, int inputDims);
};

/// Every encoding type, in the order error messages list them.
const std::vector<const EncodingType*>& encodingTypes();
/// The type called `name`, or null.
const EncodingType* findEncodingType(const std::string& name);
/// The type of `encoding` (its typeName() looked up); throws std::invalid_argument for an encoding
/// that is not registered.
const EncodingType& encodingTypeOf(const Encoding& encoding);
/// The type of `params` (its alternative's row).
const EncodingType& encodingTypeOf(const EncodingParams& params);
/// The names quoted and joined for error messages: "\"frequency\", \"one_blob\" or \"hash_grid\"".
std::string encodingTypeNames();

}  // namespace rrf
