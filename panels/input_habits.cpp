#include "panels/input_habits.h"

#include <imgui.h>

namespace rrf::panels {

void configureInput(ImGuiIO& io) { io.ConfigDragClickToInputText = true; }

}  // namespace rrf::panels
