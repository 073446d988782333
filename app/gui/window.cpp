#include "app/gui/window.h"

#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "panels/input_habits.h"

namespace rrf {

namespace {
std::string glfwErrorText;

void onGlfwError(int code, const char* description) {
    glfwErrorText = "GLFW error " + std::to_string(code) + ": " + (description ? description : "?");
}

void setupFonts(float scale) {
    ImGuiIO& io = ImGui::GetIO();
    // DejaVu Sans reads better than ImGui's bitmap font at high DPI; fall back to the built-in
    // font where it is not installed.
    const char* ttf = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    std::error_code ec;
    if (std::filesystem::is_regular_file(ttf, ec) && io.Fonts->AddFontFromFileTTF(ttf, std::round(15.f * scale))) return;
    ImFontConfig cfg;
    cfg.SizePixels = std::round(13.f * scale);
    io.Fonts->AddFontDefault(&cfg);
}
}  // namespace

Window::~Window() {
    if (imgui_) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

bool Window::create(int width, int height, const std::string& title, const std::string& configDir, bool vsync,
                    std::string& error) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) {
        error = "cannot initialise GLFW (is there a display? under CI use xvfb-run): " + glfwErrorText;
        return false;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    // Shown once its first frame is drawn (swap()): that frame builds the font atlas, compiles
    // ImGui's shaders and has llvmpipe compile their machine code at the first draw (a few hundred
    // ms), which a visible window would spend black.
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        error = "cannot create an OpenGL 3.3 core window: " + glfwErrorText;
        return false;
    }
    glfwMakeContextCurrent(window_);
    if (!gladLoadGL(glfwGetProcAddress)) {
        error = "cannot load OpenGL functions (glad)";
        return false;
    }
    glfwSwapInterval(vsync ? 1 : 0);

    float sx = 1.f, sy = 1.f;
    glfwGetWindowContentScale(window_, &sx, &sy);
    scale_ = std::clamp(std::max(sx, sy), 1.f, 4.f);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    imgui_ = true;
    ImGuiIO& io = ImGui::GetIO();
    std::error_code ec;
    std::filesystem::create_directories(configDir, ec);
    iniPath_ = ec ? std::string() : (std::filesystem::path(configDir) / "imgui.ini").string();
    io.IniFilename = iniPath_.empty() ? nullptr : iniPath_.c_str();
    ImGui::StyleColorsDark();
    ImGui::GetStyle().ScaleAllSizes(scale_);
    setupFonts(scale_);
    panels::configureInput(io);
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    // Key events go through KeyTaps (app/gui/key_taps.h) before the backend sees them; the backend's
    // other callbacks (mouse, characters, focus) stay as it installed them.
    keyTaps_ = KeyTaps([this](int key, int scancode, int action, int mods) {
        ImGui_ImplGlfw_KeyCallback(window_, key, scancode, action, mods);
    });
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
        static_cast<Window*>(glfwGetWindowUserPointer(w))->keyTaps_.event(key, scancode, action, mods);
    });
    ImGui_ImplOpenGL3_Init("#version 330 core");
    return true;
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
void Window::setShouldClose(bool close) { glfwSetWindowShouldClose(window_, close ? GLFW_TRUE : GLFW_FALSE); }
void Window::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

bool Window::waitEvents(double seconds) {
    if (seconds <= 0) {
        glfwPollEvents();
        return true;
    }
    // GLFW does not say whether an event or the timeout ended the wait; returning well before the
    // timeout means an event did.
    const double start = glfwGetTime();
    glfwWaitEventsTimeout(seconds);
    return glfwGetTime() - start < 0.9 * seconds;
}

void Window::beginFrame() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void Window::render() {
    ImGui::Render();
    keyTaps_.frameEnded();
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    glViewport(0, 0, w, h);
    glClearColor(0.08f, 0.08f, 0.09f, 1.f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Window::swap() {
    glfwSwapBuffers(window_);
    if (shown_) return;
    glfwShowWindow(window_);
    shown_ = true;
}

void Window::hide() { glfwHideWindow(window_); }

Image Window::readBackBuffer() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w <= 0 || h <= 0) return {};
    std::vector<unsigned char> px(size_t(w) * size_t(h) * 4);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    // The framebuffer holds sRGB-encoded bytes, bottom row first; Image is linear, top row first.
    // Decoding here and re-encoding in writeImage's PNG path reproduces every byte exactly.
    float lut[256];
    for (int i = 0; i < 256; ++i) lut[i] = srgbToLinear(float(i) / 255.f);
    Image img(w, h);
    for (int y = 0; y < h; ++y) {
        const unsigned char* row = &px[size_t(h - 1 - y) * size_t(w) * 4];
        for (int x = 0; x < w; ++x) img.set(x, y, Vec3(lut[row[4 * x]], lut[row[4 * x + 1]], lut[row[4 * x + 2]]));
    }
    return img;
}

}  // namespace rrf
