#pragma once
/// The model file's JSON header (nn/model.h for the format; saveModel, loadModel and parseModel
/// write and read the whole file in nn/model_file.cpp).

#include <nlohmann/json.hpp>

#include "core/nn/model.h"

namespace rrf {

/// Header of a model (everything but the payload) as JSON; what saveModel writes.
nlohmann::json modelHeader(const NetworkModel& model);

}  // namespace rrf
