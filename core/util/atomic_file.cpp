#include "core/util/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace rrf {

namespace {
std::string errnoText() { return std::strerror(errno); }
}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    // Leftovers of killed writers of the same target go first, so kills do not pile up copies.
    removeStaleTemporaryFiles(path_);
    temp_ = temporaryFileFor(path_);
    file_ = std::fopen(temp_.c_str(), "wb");
    if (!file_) throw std::runtime_error(path_ + ": cannot create temporary file '" + temp_ + "': " + errnoText());
    slot_ = registerTemporaryFile(temp_);
}

AtomicFile::~AtomicFile() {
    if (file_) std::fclose(file_);
    if (!committed_) std::remove(temp_.c_str());
    unregisterTemporaryFile(slot_);
}

void AtomicFile::write(const void* data, size_t bytes) {
    if (!file_) throw std::runtime_error(path_ + ": write after commit");
    if (bytes && std::fwrite(data, 1, bytes, file_) != bytes)
        throw std::runtime_error(path_ + ": write failed: " + errnoText());
}

void AtomicFile::commit() {
    if (!file_) throw std::runtime_error(path_ + ": commit called twice");
    bool ok = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
    const std::string err = ok ? "" : errnoText();
    ok = (std::fclose(file_) == 0) && ok;
    file_ = nullptr;
    if (!ok) throw std::runtime_error(path_ + ": flushing '" + temp_ + "' failed: " + err);
    crashPoint("commit " + std::filesystem::path(path_).filename().string());
    if (std::rename(temp_.c_str(), path_.c_str()) != 0)
        throw std::runtime_error(path_ + ": rename from '" + temp_ + "' failed: " + errnoText());
    committed_ = true;
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
