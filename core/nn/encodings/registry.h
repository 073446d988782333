#pragma once
/// The encoding types by name, as tiny-cuda-nn's "otype" registry (docs/design.md §10a): each type's
/// name, its hyperparameter keys, the most inputs one component may read, its component id in the
/// GLSL predictor's network texture and its reader, in one row kept beside its implementation
/// (FrequencyEncoding::type() in encodings/frequency.cpp, …). The "encoding" reader
/// (InputEncoding::fromJson), the model file and the network texture look types up here, so a type's
/// name is spelled once and a new encoding is one implementation plus one entry of encodingTypes().

#include <memory>
#include <string>
#include <vector>

#include "core/nn/encoding.h"
#include "core/util/json_reader.h"

namespace rrf {

/// One encoding type.
struct EncodingType {
    const char* name;               ///< the component's "type" in JSON and Encoding::typeName()
    std::vector<std::string> keys;  ///< its hyperparameter keys (a component also has "type" and "inputs")
    int maxInputs;                  ///< most inputs one component of this type reads
    int glslId;                     ///< component type in the network texture (shaders/encoding.glsl)
    /// Builds the component from its JSON object (its hyperparameter keys, defaults where absent) for
    /// `inputDims` inputs; InputError names the reader's file and the pointer of a bad value.
    std::shared_ptr<const Encoding> (*fromJson)(const JsonReader& component, int inputDims);
};

/// Every encoding type, in the order error messages list them.
const std::vector<const EncodingType*>& encodingTypes();
/// The type called `name`, or null.
const EncodingType* findEncodingType(const std::string& name);
/// The type of `encoding` (its typeName() looked up); throws std::invalid_argument for an encoding
/// that is not registered.
const EncodingType& encodingTypeOf(const Encoding& encoding);
/// The names quoted and joined for error messages: "\"frequency\", \"one_blob\" or \"hash_grid\"".
std::string encodingTypeNames();

}  // namespace rrf
