// The keyboard shortcuts table (see shortcuts.h).
#include "app/gui/shortcuts.h"

// Key codes only: no GL header, so that glad (app/gl, window.cpp) may come after it in a unity build.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace rrf {

const std::vector<Shortcut>& shortcuts() {
    static const std::vector<Shortcut> table = {
        {ShortcutAction::Help, GLFW_KEY_F1, false, false, "F1", "show or hide this Help window"},
        {ShortcutAction::Open, GLFW_KEY_O, true, false, "Ctrl+O", "open a project"},
        {ShortcutAction::Save, GLFW_KEY_S, true, false, "Ctrl+S", "save the project"},
        {ShortcutAction::Undo, GLFW_KEY_Z, true, false, "Ctrl+Z",
         "undo a setting edit (render, sampling, network, trainer, prediction, light position)"},
        {ShortcutAction::Redo, GLFW_KEY_Z, true, true, "Ctrl+Shift+Z", "redo the setting edit undone"},
        {ShortcutAction::FrameOverlay, GLFW_KEY_F3, false, false, "F3", "frame time overlay (UI frame, GLSL and CPU prediction)"},
        {ShortcutAction::Quit, GLFW_KEY_Q, true, false, "Ctrl+Q", "quit (asks about unsaved changes)"},
    };
    return table;
}

const char* shortcutKeys(ShortcutAction action) {
    for (const Shortcut& s : shortcuts())
        if (s.action == action) return s.keys;
    return nullptr;
}

std::vector<panels::ShortcutInfo> shortcutInfos() {
    std::vector<panels::ShortcutInfo> out;
    for (const Shortcut& s : shortcuts()) out.push_back({s.keys, s.what});
    return out;
}

}  // namespace rrf
