#pragma once
/// Key taps shorter than a frame. Dear ImGui 1.86 reads keys as a down/up state per frame
/// (io.KeysDown), and its GLFW backend writes that state straight from GLFW's key events. A tap whose
/// press and release both arrive between two frames (a quick typist, a loaded machine, a frame of
/// 100 ms) leaves the key up at the next frame, so ImGui never sees it pressed and the shortcut or
/// the typed key is lost. KeyTaps sits between GLFW and the backend: a release of a key pressed since
/// the current frame began is held back until that frame has read the key as down
/// (frameStarted, right after ImGui::NewFrame), so the frame sees the press and the next one the
/// release. Every other event passes through at once, in order.

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
    /// Call after ImGui::NewFrame: the frame has read the keys, so the releases held back for it go
    /// through now and the next frame sees them.
    void frameStarted();
    /// Releases held back for the current frame (for tests).
    size_t heldReleases() const { return held_.size(); }

private:
    struct Event {
        int key, scancode, action, mods;
    };
    Forward forward_;
    std::vector<int> pressedThisFrame_;  ///< keys pressed since the last frameStarted
    std::vector<Event> held_;            ///< their releases, in arrival order
};

}  // namespace rrf
