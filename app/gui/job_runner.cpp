#include "app/gui/job_runner.h"

#include "app/gui/worker_priority.h"

#include <algorithm>

namespace rrf {

const char* jobKindName(JobKind kind) {
    switch (kind) {
        case JobKind::Render: return "render";
        case JobKind::Generate: return "generate";
        case JobKind::Train: return "train";
        case JobKind::Evaluate: return "evaluate";
        case JobKind::Predict: return "predict";
        case JobKind::Sweep: return "sweep";
        case JobKind::Compare: return "compare";
        case JobKind::Overlay: return "view overlay";  // the leaf tint and the FLIP map
        case JobKind::LightGrid: return "light grid";
        case JobKind::Spread: return "spread map";
        case JobKind::ReadBack: return "read back";
    }
    return "job";
}

bool jobsConflict(JobKind a, JobKind b) {
    if (a == JobKind::ReadBack || b == JobKind::ReadBack) return false;  // writes nothing
    if (a == b) return true;  // two of a kind would write the same outputs
    // A sweep renders, generates and trains in its own memory and writes no project files; it only
    // competes for the cores, which the user decides about.
    if (a == JobKind::Sweep || b == JobKind::Sweep) return false;
    // So does a light grid beside other jobs: references into the store, predictions of the models
    // it holds (two of them would write the same files: a == b above).
    if (a == JobKind::LightGrid || b == JobKind::LightGrid) return false;
    if (a == JobKind::Compare || b == JobKind::Compare) return false;  // its own models, copied images
    if (a == JobKind::Overlay || b == JobKind::Overlay) return false;  // shared read-only models
    if (a == JobKind::Spread || b == JobKind::Spread) return false;    // so does the spread map
    auto pair = [&](JobKind x, JobKind y) { return (a == x && b == y) || (a == y && b == x); };
    // Training reads the dataset being generated; evaluation reads the models being trained and
    // compares against the ground truth being rendered.
    // A CPU prediction reads the models a training job is about to replace.
    return pair(JobKind::Generate, JobKind::Train) || pair(JobKind::Train, JobKind::Evaluate) ||
           pair(JobKind::Train, JobKind::Predict) ||
           pair(JobKind::Render, JobKind::Evaluate);
}

void JobContext::setProgress(double fraction) {
    std::lock_guard<std::mutex> lock(mutex_);
    progress_ = std::clamp(fraction, 0.0, 1.0);
}

void JobContext::setStatus(const std::string& status) {
    std::lock_guard<std::mutex> lock(mutex_);
    status_ = status;
}

void JobContext::onCancel(std::function<void()> hook) {
    std::lock_guard<std::mutex> lock(mutex_);
    cancelHook_ = std::move(hook);
    if (cancel_.load() && cancelHook_) cancelHook_();  // cancelled before the hook was installed
}

StageObserver JobContext::stageObserver() {
    StageObserver o;
    o.cancel = &cancel_;
    o.progress = [this](double f) { setProgress(f); };
    o.status = [this](const std::string& st) { setStatus(st); };
    o.message = [this](const std::string& m) { post(m); };
    return o;
}

void JobContext::post(const std::string& line) {
    std::lock_guard<std::mutex> lock(mutex_);
    messages_.push_back(line);
}

std::vector<std::string> JobContext::takeMessages() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> out;
    out.swap(messages_);
    return out;
}

JobRunner::~JobRunner() {
    cancelAll();
    waitAll();
}

int JobRunner::start(JobKind kind, const std::string& name, std::function<void(JobContext&)> work, std::string* why) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& e : entries_) {
        if (!e->done.load() && jobsConflict(kind, e->info.kind)) {
            if (why)
                *why = "cannot start " + std::string(jobKindName(kind)) + " while '" + e->info.name +
                       "' is running; stop it first";
            return 0;
        }
    }
    auto entry = std::make_unique<Entry>();
    entry->info.id = nextId_++;
    entry->info.kind = kind;
    entry->info.name = name;
    entry->context = std::make_shared<JobContext>();
    entry->start = std::chrono::steady_clock::now();
    Entry* raw = entry.get();
    std::shared_ptr<JobContext> ctx = entry->context;
    entry->thread = std::thread([raw, ctx, work = std::move(work)] {
        std::string error;
        try {
            // Below the UI thread, its parallel loops included (app/gui/worker_priority.h).
            runAtBackgroundPriority([&] { work(*ctx); });
        } catch (const std::exception& ex) {
            error = ex.what();
        } catch (...) {
            error = "unknown exception";
        }
        if (!error.empty()) {
            std::lock_guard<std::mutex> l(ctx->mutex_);
            ctx->error_ = error;
            ctx->status_ = "failed: " + error;
        }
        // `done` is the worker's last write: after it, the UI thread may join and read everything.
        raw->done.store(true);
    });
    const int id = entry->info.id;
    entries_.push_back(std::move(entry));
    return id;
}

void JobRunner::cancel(int id) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& e : entries_) {
        if (e->info.id != id) continue;
        e->context->cancel_.store(true);
        std::function<void()> hook;
        {
            std::lock_guard<std::mutex> l(e->context->mutex_);
            hook = e->context->cancelHook_;
        }
        if (hook) hook();
        e->info.cancelled = true;
    }
}

void JobRunner::cancelAll() {
    std::vector<int> ids;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (auto& e : entries_) ids.push_back(e->info.id);
    }
    for (int id : ids) cancel(id);
}

JobInfo JobRunner::snapshot(const Entry& e) const {
    JobInfo info = e.info;
    {
        std::lock_guard<std::mutex> l(e.context->mutex_);
        info.progress = e.context->progress_;
        info.status = e.context->status_;
        info.error = e.context->error_;
    }
    info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - e.start).count();
    info.running = !e.done.load();
    // Linear extrapolation; only once there is enough progress for it to mean something.
    if (info.progress > 0.02 && info.progress < 1.0) info.etaSeconds = info.seconds * (1.0 - info.progress) / info.progress;
    info.failed = !info.error.empty();
    return info;
}

std::vector<JobInfo> JobRunner::jobs() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<JobInfo> out;
    for (const auto& e : entries_)
        if (!e->done.load()) out.push_back(snapshot(*e));
    return out;
}

bool JobRunner::running(int id) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::any_of(entries_.begin(), entries_.end(),
                       [&](const auto& e) { return e->info.id == id && !e->done.load(); });
}

std::optional<JobInfo> JobRunner::info(int id) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& e : entries_)
        if (e->info.id == id && !e->done.load()) return snapshot(*e);
    return std::nullopt;
}

std::shared_ptr<JobContext> JobRunner::context(int id) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& e : entries_)
        if (e->info.id == id) return e->context;
    return nullptr;
}

bool JobRunner::idle() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::all_of(entries_.begin(), entries_.end(), [](const auto& e) { return e->done.load(); });
}

bool JobRunner::drained() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_.empty();
}

std::vector<JobInfo> JobRunner::takeFinished() {
    std::vector<std::unique_ptr<Entry>> finished;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (auto it = entries_.begin(); it != entries_.end();) {
            if ((*it)->done.load()) {
                finished.push_back(std::move(*it));
                it = entries_.erase(it);
            } else {
                ++it;
            }
        }
    }
    std::vector<JobInfo> out;
    for (auto& e : finished) {
        e->thread.join();
        out.push_back(snapshot(*e));
    }
    return out;
}

void JobRunner::waitAll() {
    while (!idle()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    takeFinished();
}

}  // namespace rrf
