#pragma once
/// The JSON of a network's built encoding (nn/encoding.h): the "components" array a model file
/// stores (nn/model_file.cpp), every key of every component written, and its reader.

#include <nlohmann/json.hpp>

#include "core/nn/derived_inputs.h"
#include "core/nn/encoding.h"
#include "core/util/json_reader.h"

namespace rrf {

/// Reads an "encoding" array for a network of `inputs` record inputs (12 + brdfCount) and the
/// `derived` inputs; InputError names the reader's file and the JSON pointer of an unknown type
/// or key, a wrong value, an unknown or repeated input group, or "reflected" in a network that
/// does not derive it. An empty array is the identity.
InputEncoding inputEncodingFromJson(const JsonReader& r, int inputs, const DerivedInputs& derived = {});
/// The array, every key of every component written (what a model file stores).
nlohmann::json toJson(const InputEncoding& encoding);

}  // namespace rrf
