#include "app/gl/gl_worker.h"

#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include "app/gl/gl_context.h"

namespace rrf {

GlWorker::GlWorker() {
    window_ = createOffscreenWindow("rrf GL worker");
    std::future<void> started = started_.get_future();
    thread_ = std::thread([this] { loop(); });
    try {
        started.get();
    } catch (...) {
        thread_.join();
        glfwDestroyWindow(window_);
        throw;
    }
}

GlWorker::~GlWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
    glfwDestroyWindow(window_);  // the thread released the context before it ended
}

int GlWorker::pending() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return int(tasks_.size()) + running_;
}

void GlWorker::enqueue(std::function<void()> task) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        tasks_.push_back(std::move(task));
    }
    wake_.notify_one();
}

void GlWorker::loop() {
    glfwMakeContextCurrent(window_);
    if (glfwGetCurrentContext() != window_) {
        started_.set_exception(std::make_exception_ptr(
            GlContextError("the GL worker could not make its OpenGL context current")));
        return;
    }
    // The window's thread loaded the entry points already (they are the same for every context
    // under GLX); a program without a window loads them here.
    if (!GLAD_GL_VERSION_3_3 && gladLoadGL(glfwGetProcAddress) == 0) {
        glfwMakeContextCurrent(nullptr);
        started_.set_exception(std::make_exception_ptr(
            GlContextError("glad could not load the OpenGL 3.3 core functions for the GL worker")));
        return;
    }
    started_.set_value();
    for (;;) {
        std::function<void()> task;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
            if (tasks_.empty()) break;  // stopping, and every posted task has run
            task = std::move(tasks_.front());
            tasks_.pop_front();
            ++running_;
        }
        task();  // a packaged task: its exception goes to its future
        std::lock_guard<std::mutex> lock(mutex_);
        --running_;
    }
    glFinish();
    glfwMakeContextCurrent(nullptr);
}

}  // namespace rrf
