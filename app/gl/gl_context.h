#pragma once
/// An offscreen OpenGL 3.3 core context: a hidden GLFW window (GLFW_VISIBLE false) whose default
/// framebuffer is never shown; rendering goes to framebuffer objects. Used by the GL tests, the GL
/// benchmark and command-line tools; the GUI uses its own window's context instead.
///
/// Needs an X server (a real display or Xvfb; Mesa's llvmpipe serves when there is no GPU).

#include <stdexcept>
#include <string>

struct GLFWwindow;

namespace rrf {

/// Thrown when no context can be made (no X server, no OpenGL 3.3 core driver, loader failure).
class GlContextError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Initialises GLFW and creates a hidden window whose OpenGL 3.3 core, forward-compatible context
/// is not made current (GLFW restores the calling thread's context). Main thread only, as every
/// GLFW window. Throws GlContextError with GLFW's own message on any failure.
GLFWwindow* createOffscreenWindow(const char* title);

class GlContext {
public:
    /// Initialises GLFW, creates the hidden window with an OpenGL 3.3 core, forward-compatible
    /// context, makes it current on the calling thread and loads the GL functions with glad.
    /// Throws GlContextError with GLFW's own message on any failure.
    GlContext();
    /// Destroys the window. GLFW itself stays initialised for the rest of the process: glfwTerminate
    /// would also destroy windows that other code (the GUI) owns.
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    /// Makes this context current on the calling thread (GL contexts are per thread).
    void makeCurrent();
    /// GL_RENDERER / GL_VERSION strings, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    std::string renderer() const;
    std::string version() const;

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace rrf
