#pragma once
/// The workbench window: GLFW, an OpenGL 3.3 core context loaded with glad, and Dear ImGui with its
/// GLFW and OpenGL3 backends. High-DPI aware (font and style scaled by the monitor content scale);
/// ImGui's ini file lives in the per-user config directory, not in the working directory.

#include <string>

#include "app/gui/key_taps.h"
#include "core/util/image.h"

struct GLFWwindow;

namespace rrf {

class Window {
public:
    Window() = default;
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    /// Opens the window and initialises GL and ImGui. On failure returns false with `error` set.
    /// `configDir` receives imgui.ini; `vsync` off lets scripted runs go as fast as they can.
    bool create(int width, int height, const std::string& title, const std::string& configDir, bool vsync,
                std::string& error);

    bool shouldClose() const;
    void setShouldClose(bool close);
    void setTitle(const std::string& title);
    /// Waits for events at most `seconds` (0 = just poll): the UI redraws on input and at least
    /// this often, without spinning a core that the renderer needs. Returns true when an event
    /// (rather than the timeout) ended the wait.
    bool waitEvents(double seconds);
    void beginFrame();
    /// Renders ImGui's draw data into the back buffer (call swap() after any read-back).
    void render();
    /// Presents the frame; the first call also shows the window, which stays hidden until its
    /// first frame is drawn.
    void swap();
    /// Takes the window off the screen at once (on quit): the jobs and the GL worker then wind down
    /// behind it, seconds when a shader compile is under way, instead of in a window that no longer
    /// answers.
    void hide();

    /// Reads the back buffer after render() into a linear-RGB image (top row first).
    Image readBackBuffer() const;
    float contentScale() const { return scale_; }

private:
    GLFWwindow* window_ = nullptr;
    bool imgui_ = false;
    bool shown_ = false;
    float scale_ = 1.f;
    std::string iniPath_;  ///< must outlive ImGui, which keeps the pointer
    /// GLFW's key events on their way to ImGui's backend, so that taps shorter than a frame count.
    KeyTaps keyTaps_{nullptr};
};

}  // namespace rrf
