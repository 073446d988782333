#pragma once
/// The JSON of a network's derived inputs (nn/derived_inputs.h): {"reflected": bool}, in the
/// project's "network" section, its "objects" entries and a model file's "input_encoding".

#include <nlohmann/json.hpp>

#include "core/nn/derived_inputs.h"
#include "core/util/json_reader.h"

namespace rrf {

/// Reads {"reflected": bool}; InputError names the file and pointer of an unknown key or a
/// value that is not a boolean.
DerivedInputs derivedInputsFromJson(const JsonReader& r);
/// Every key written.
nlohmann::json toJson(const DerivedInputs& d);

}  // namespace rrf
