#include "app/gui/job_session.h"

namespace rrf {

double JobSessionBase::progress() const {
    const std::optional<JobInfo> info = id_ ? runner_.info(id_) : std::nullopt;
    return info ? info->progress : 0.0;
}

void JobSessionBase::cancel() {
    if (id_) runner_.cancel(id_);
}

void JobSessionBase::drop() {
    // The id stays: running() is true until the cancelled worker has returned, so a new job of this
    // kind waits for it (GroundTruthController::restart starts the render again once the old one stopped).
    cancel();
    context_.reset();
    forgetResult();
}

bool JobSessionBase::launch(const std::string& name, std::function<void(JobContext&)> work, std::string* why) {
    std::string reason;
    const int id = runner_.start(kind_, name, std::move(work), &reason);
    if (!id) {
        if (why) *why = reason;
        else log_.error(std::string(jobKindName(kind_)) + " refused: " + reason);
        return false;
    }
    // The previous job's remaining lines belong before this one's.
    forwardMessages();
    id_ = id;
    context_ = runner_.context(id);
    return true;
}

void JobSessionBase::forwardMessages() {
    if (!context_) return;
    for (const std::string& line : context_->takeMessages()) log_.info(std::string(jobKindName(kind_)) + ": " + line);
}

}  // namespace rrf
