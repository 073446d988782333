#include "app/gl/gl_context.h"

#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include <cstdlib>

namespace rrf {

namespace {

// GLFW reports errors through a process-wide callback; the constructor installs this one only while
// it runs (restoring whatever the application had) and turns the last message into the exception.
thread_local std::string lastGlfwError;

void recordGlfwError(int code, const char* message) {
    lastGlfwError = "GLFW error " + std::to_string(code) + ": " + (message ? message : "(no message)");
}

class ErrorCallbackScope {
public:
    ErrorCallbackScope() : previous_(glfwSetErrorCallback(recordGlfwError)) { lastGlfwError.clear(); }
    ~ErrorCallbackScope() { glfwSetErrorCallback(previous_); }
    std::string message() const { return lastGlfwError.empty() ? "no details from GLFW" : lastGlfwError; }

private:
    GLFWerrorfun previous_;
};

std::string glString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : std::string("(unknown)");
}

}  // namespace

GLFWwindow* createOffscreenWindow(const char* title) {
    ErrorCallbackScope errors;
    if (!glfwInit())
        throw GlContextError("cannot initialise GLFW (is an X server running? DISPLAY=" +
                             std::string(std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "unset") +
                             "): " + errors.message());
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    // The window is never shown; its size does not limit the FBOs rendered into.
    GLFWwindow* window = glfwCreateWindow(16, 16, title, nullptr, nullptr);
    glfwDefaultWindowHints();
    if (!window) throw GlContextError(std::string("cannot create an OpenGL 3.3 core context (") + title + "): " + errors.message());
    return window;
}

GlContext::GlContext() {
    window_ = createOffscreenWindow("rrf offscreen");
    glfwMakeContextCurrent(window_);
    if (gladLoadGL(glfwGetProcAddress) == 0) {
        glfwDestroyWindow(window_);
        window_ = nullptr;
        throw GlContextError("glad could not load the OpenGL 3.3 core functions");
    }
}

GlContext::~GlContext() {
    if (!window_) return;
    if (glfwGetCurrentContext() == window_) glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(window_);
}

void GlContext::makeCurrent() { glfwMakeContextCurrent(window_); }

std::string GlContext::renderer() const { return glString(GL_RENDERER); }
std::string GlContext::version() const { return glString(GL_VERSION); }

}  // namespace rrf
