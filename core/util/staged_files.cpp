// Staged files (staged_files.h): plain writes into a staging directory, synced together once.
#include "core/util/staged_files.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/temp_files.h"

namespace rrf {

namespace fs = std::filesystem;

namespace {
int fsyncFile(int fd, const char*) { return ::fsync(fd); }
std::atomic<StagedFileFlush> flushFile{&fsyncFile};
}  // namespace

void setStagedFileFlushForTesting(StagedFileFlush flush) { flushFile = flush ? flush : &fsyncFile; }

void writeStagedFile(const std::string& path, const std::string& bytes) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    // The staging directory is the target's: a failure here is the target's, and nothing of it exists yet.
    if (!f) throw OutputError(path, std::string("cannot write the file: ") + std::strerror(errno), "no file was created");
    const bool written = bytes.empty() || std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    std::string err = written ? "" : std::strerror(errno);
    const bool closed = std::fclose(f) == 0;
    if (written && !closed) err = std::strerror(errno);
    if (!(written && closed)) throw OutputError(path, "write failed: " + err, "no file was created");
    crashPoint("commit " + fs::path(path).filename().string());
}

void syncStagedDirectory(const std::string& dir) {
    std::vector<std::string> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec)) files.push_back(it->path().string());
    if (ec) throw OutputError(dir, "cannot list the new files: " + ec.message(), "");
    std::atomic<size_t> next{0};
    std::mutex failureMutex;
    std::string failedFile, failure;  // the first file that could not be synced, and why
    auto syncSome = [&] {
        for (size_t i = next++; i < files.size(); i = next++) {
            const int fd = ::open(files[i].c_str(), O_RDONLY);
            const bool synced = fd >= 0 && flushFile.load()(fd, files[i].c_str()) == 0;
            const int err = errno;
            if (fd >= 0) ::close(fd);
            if (synced) continue;
            std::lock_guard<std::mutex> lock(failureMutex);
            if (failedFile.empty()) {
                failedFile = files[i];
                failure = std::strerror(err);
            }
        }
    };
    // A few fsyncs in flight at once: each waits mostly on the device, and concurrent ones share a
    // journal commit; more threads than that only add start-up cost.
    const size_t threads = std::min<size_t>(files.size(), 8);
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(syncSome);
    syncSome();
    for (std::thread& t : pool) t.join();
    if (!failedFile.empty()) throw OutputError(failedFile, "cannot be flushed to disk: " + failure, "");
    (void)syncDirectory(dir);
}

}  // namespace rrf
