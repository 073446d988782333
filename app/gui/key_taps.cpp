#include "app/gui/key_taps.h"

#include <algorithm>

#include <GLFW/glfw3.h>

namespace rrf {

void KeyTaps::event(int key, int scancode, int action, int mods) {
    const bool pressedThisFrame =
        std::find(pressedThisFrame_.begin(), pressedThisFrame_.end(), key) != pressedThisFrame_.end();
    if (action == GLFW_RELEASE && pressedThisFrame) {
        held_.push_back({key, scancode, action, mods});
        return;
    }
    if (action == GLFW_PRESS) {
        if (!pressedThisFrame) pressedThisFrame_.push_back(key);
        // A second press of a key whose release is held: that release happened before this press,
        // so it goes first (the key was up in between; the frame still sees it down).
        auto it = std::find_if(held_.begin(), held_.end(), [&](const Event& e) { return e.key == key; });
        if (it != held_.end()) {
            forward_(it->key, it->scancode, it->action, it->mods);
            held_.erase(it);
        }
    }
    forward_(key, scancode, action, mods);
}

void KeyTaps::frameEnded() {
    for (const Event& e : held_) forward_(e.key, e.scancode, e.action, e.mods);
    held_.clear();
    pressedThisFrame_.clear();
}

}  // namespace rrf
