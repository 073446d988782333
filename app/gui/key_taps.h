#pragma once
/// Key taps shorter than a frame. Dear ImGui 1.86 reads keys as a down/up state per frame
/// (io.KeysDown), and its GLFW backend writes that state straight from GLFW's key events. A tap whose
/// press and release both arrive between two frames (a quick typist, a loaded machine, a frame of
/// 100 ms) leaves the key up at the next frame, so ImGui never sees it pressed and the shortcut or
/// the typed key is lost. KeyTaps sits between GLFW and the backend: a release of a key pressed since
/// the last frame ended is held back until the next frame has run (frameEnded, after the UI has
/// drawn and acted), so that whole frame sees the key down and the one after sees it up. The whole
/// frame matters: the backend recomputes io.KeyCtrl/KeyShift at once from the keys' states, and the
/// shortcut table compares them while the UI runs, so a Ctrl+S tap needs Ctrl down until then.
/// Every other event passes through at once, in order.

#include <functional>
#include <vector>

namespace rrf {

class KeyTaps {
public:
    /// Where events go (the ImGui GLFW backend's key callback; a test's stand-in), with GLFW's
    /// arguments: key, scancode, action (GLFW_PRESS, GLFW_RELEASE, GLFW_REPEAT), modifier bits.
    using Forward = std::function<void(int key, int scancode, int action, int mods)>;

    explicit KeyTaps(Forward forward) : forward_(std::move(forward)) {}

    /// One key event from GLFW (the window's key callback).
    void event(int key, int scancode, int action, int mods);
    /// Call once the frame's UI has run (after ImGui::Render): the releases held back for it go
    /// through now and the next frame sees them.
    void frameEnded();
    /// Releases held back for the coming frame (for tests).
    size_t heldReleases() const { return held_.size(); }

private:
    struct Event {
        int key, scancode, action, mods;
    };
    Forward forward_;
    std::vector<int> pressedThisFrame_;  ///< keys pressed since the last frameEnded
    std::vector<Event> held_;            ///< their releases, in arrival order
};

}  // namespace rrf
