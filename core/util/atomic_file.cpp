#include "core/util/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include "core/util/error.h"

namespace rrf {

namespace {
std::string errnoText() { return std::strerror(errno); }
}  // namespace

bool syncDirectory(const std::string& dir) {
    const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd < 0) return false;
    const bool ok = ::fsync(fd) == 0;
    ::close(fd);
    return ok;
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    std::error_code ec;
    existed_ = std::filesystem::exists(path_, ec);
    // Leftovers of killed writers of the same target go first, so kills do not pile up copies.
    removeStaleTemporaryFiles(path_);
    temp_ = temporaryFileFor(path_);
    file_ = std::fopen(temp_.c_str(), "wb");
    // The temporary lies beside the destination: what stops it (no such directory, no permission,
    // no space) stops the destination too, so the error is the destination's.
    if (!file_) fail("cannot write the file: " + errnoText());
    slot_ = registerTemporaryFile(temp_);
}

void AtomicFile::fail(const std::string& problem) const {
    throw OutputError(path_, problem, existed_ ? "the previous file is kept" : "no file was created");
}

AtomicFile::~AtomicFile() {
    if (file_) std::fclose(file_);
    if (!committed_) std::remove(temp_.c_str());
    unregisterTemporaryFile(slot_);
}

void AtomicFile::write(const void* data, size_t bytes) {
    if (!file_) throw std::logic_error(path_ + ": write after commit");
    if (bytes && std::fwrite(data, 1, bytes, file_) != bytes) fail("write failed: " + errnoText());
}

void AtomicFile::commit() {
    if (!file_) throw std::logic_error(path_ + ": commit called twice");
    bool ok = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
    std::string err = ok ? "" : errnoText();
    const bool closed = std::fclose(file_) == 0;
    if (ok && !closed) err = errnoText();
    file_ = nullptr;
    // Buffered bytes reach the disk here, so a full disk usually shows up now rather than in write().
    if (!(ok && closed)) fail("write failed: " + err);
    crashPoint("commit " + std::filesystem::path(path_).filename().string());
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) fail("cannot replace the file: " + errnoText());
    committed_ = true;
    // Best effort (see syncDirectory): the file is complete and in place either way.
    syncDirectory(std::filesystem::path(path_).parent_path().string());
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
    AtomicFile f(path);
    f.write(bytes);
    f.commit();
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open for reading: " + errnoText());
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw std::runtime_error(path + ": read failed");
    return ss.str();
}

}  // namespace rrf
