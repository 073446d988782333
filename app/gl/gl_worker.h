#pragma once
/// A thread of its own with an OpenGL context of its own, for the GL work of the live prediction
/// that must not run on the UI thread (issue 29: no UI-thread stall over 100 ms).
///
/// Why a second context and not a shared one: Mesa's llvmpipe compiles a program's machine code at
/// its first draw, seconds for the prediction shader, and keeps that code per context (it offers
/// no shareable shaders). A program compiled in another context and drawn there once would be
/// compiled again at the UI context's first draw. So the context that draws the prediction is the
/// worker's: it builds the GlslPredictor, compiles and warms its programs up, and renders, and
/// only images (read back to the CPU) cross to the UI thread. The context shares nothing with the
/// window's.
///
/// Tasks run one at a time, in the order they were posted, with the worker's context current.
/// Objects holding GL names made on the worker must be destroyed on it too (post their deletion).
///
/// Construction and destruction happen on the main thread (GLFW creates and destroys windows
/// there only); GLFW must be initialised. The GL functions are loaded with glad if no one has
/// loaded them yet (with GLX the entry points do not depend on the context).

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>

struct GLFWwindow;

namespace rrf {

/// True when `f` (a future from GlWorker::post) holds its result: the UI polls without waiting.
template <class T>
bool resultReady(const std::future<T>& f) {
    return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

class GlWorker {
public:
    /// Creates the hidden window of an OpenGL 3.3 core context and starts the thread, which makes
    /// the context current. Throws GlContextError (app/gl/gl_context.h) with GLFW's message.
    GlWorker();
    /// Runs the tasks already posted, stops the thread, then destroys the window.
    ~GlWorker();
    GlWorker(const GlWorker&) = delete;
    GlWorker& operator=(const GlWorker&) = delete;

    /// Queues `task` and returns the future of its result (or exception). The task, and what it
    /// captured, is destroyed on the worker after it ran.
    template <class F>
    std::future<std::invoke_result_t<F>> post(F&& task) {
        using R = std::invoke_result_t<F>;
        auto packaged = std::make_shared<std::packaged_task<R()>>(std::forward<F>(task));
        std::future<R> result = packaged->get_future();
        // Only the queue holds the task, so what it captured is destroyed on the worker too.
        enqueue([p = std::move(packaged)] { (*p)(); });
        return result;
    }
    /// Runs `task` on the worker and waits for it: its result, or its exception rethrown here.
    template <class F>
    std::invoke_result_t<F> run(F&& task) {
        return post(std::forward<F>(task)).get();
    }
    /// Tasks queued or running.
    int pending() const;

private:
    void enqueue(std::function<void()> task);
    void loop();

    GLFWwindow* window_ = nullptr;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> tasks_;
    int running_ = 0;
    bool stopping_ = false;
    std::promise<void> started_;  ///< set by the thread once its context is current (or why not)
    std::thread thread_;
};

}  // namespace rrf
