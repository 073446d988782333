#pragma once
/// A full disk for tests that cannot mount one: RLIMIT_FSIZE makes the kernel refuse any write that
/// would grow a regular file past the limit (EFBIG, "File too large"), which reaches the writers
/// exactly where ENOSPC would — on a short write or at the final flush — without root or a small
/// file system. SIGXFSZ, which such a write also raises, is ignored meanwhile (its default action
/// ends the process). Pipes and terminals are not regular files, so test output is unaffected.

#include <csignal>

#include <sys/resource.h>

namespace rrf::test {

class FileSizeLimit {
public:
    /// Limits regular files written from now on to `bytes` until destruction.
    explicit FileSizeLimit(rlim_t bytes) {
        ok_ = ::getrlimit(RLIMIT_FSIZE, &saved_) == 0;
        oldHandler_ = std::signal(SIGXFSZ, SIG_IGN);
        rlimit small = saved_;
        small.rlim_cur = bytes;
        ok_ = ok_ && ::setrlimit(RLIMIT_FSIZE, &small) == 0;
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &saved_);
        std::signal(SIGXFSZ, oldHandler_);
    }
    FileSizeLimit(const FileSizeLimit&) = delete;
    FileSizeLimit& operator=(const FileSizeLimit&) = delete;

    /// False if the limit could not be set (the test then proves nothing and should fail).
    bool active() const { return ok_; }

private:
    rlimit saved_{};
    void (*oldHandler_)(int) = nullptr;
    bool ok_ = false;
};

}  // namespace rrf::test
