#pragma once
/// The workbench's keyboard shortcuts, one table (issue 29: a shortcuts list and a Help window): the
/// key handler acts on it, the menus take their labels from it, and the Help window (F1) lists it,
/// so what is advertised is what works.

#include <vector>

#include "panels/panels.h"

namespace rrf {

/// What a shortcut does.
enum class ShortcutAction { Open, Save, Quit, Undo, Redo, FrameOverlay, Help };

struct Shortcut {
    ShortcutAction action;
    int key;            ///< GLFW key code (ImGui 1.86 indexes keys by the backend's codes)
    bool ctrl;          ///< with Ctrl held
    bool shift;         ///< with Shift held
    const char* keys;   ///< as menus and the Help window show it, e.g. "Ctrl+O"
    const char* what;   ///< what it does, for the Help window
};

/// Every shortcut, in the order the Help window lists them.
const std::vector<Shortcut>& shortcuts();

/// The label of `action`'s shortcut ("Ctrl+S"), for a menu item.
const char* shortcutKeys(ShortcutAction action);

/// The table as the Help window takes it (panels know no key codes).
std::vector<panels::ShortcutInfo> shortcutInfos();

}  // namespace rrf
