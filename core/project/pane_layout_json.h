#pragma once
/// The project's "layout" section (core/project/pane_layout.h) in JSON: the file codec of the pane
/// tree and its floating windows.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/project/pane_layout.h"
#include "core/util/json_reader.h"

namespace rrf {

/// {"root": node[, "floating": [...]]}; nodes as in pane_layout.h's header comment.
nlohmann::json toJson(const PaneLayout& layout);
/// Reads the section. A damaged layout must never make the workspace unusable (nor the project
/// unopenable): a damaged tree is replaced by the default arrangement, an unknown or repeated tab
/// is dropped (a floating one too, and a floating panel that a pane also holds), a panel no pane
/// or window holds is added to the first pane, an out-of-range fraction is
/// clamped, and each repair is described in `warnings` (file, JSON pointer, what was expected).
/// The old form {"left", "bottom"} is read as the default arrangement with those fractions.
PaneLayout paneLayoutFromJson(const JsonReader& section, std::vector<std::string>& warnings);

}  // namespace rrf
