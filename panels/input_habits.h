#pragma once
/// How the workbench's widgets answer the mouse and keyboard, set once on ImGui's IO by the window
/// (and by the panel tests, so they drive the widgets as a user's window does).
///  - A single click on a numeric drag field, released without dragging, opens it for typing (the
///    habit of spreadsheet and DCC tools: Blender, Houdini); a drag still changes the value, and
///    Ctrl+click and double-click keep working. ImGui 1.86 does this with
///    ConfigDragClickToInputText, which it leaves off by default.

struct ImGuiIO;

namespace rrf::panels {

/// Sets the habits above on `io` (once, after ImGui::CreateContext).
void configureInput(ImGuiIO& io);

}  // namespace rrf::panels
