#include "core/util/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace rrf {

namespace {
std::atomic<unsigned> g_counter{0};

std::string errnoText() { return std::strerror(errno); }
}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    temp_ = path_ + "." + std::to_string(::getpid()) + "." + std::to_string(g_counter++) + ".tmp";
    file_ = std::fopen(temp_.c_str(), "wb");
    if (!file_) throw std::runtime_error(path_ + ": cannot create temporary file '" + temp_ + "': " + errnoText());
}

AtomicFile::~AtomicFile() {
    if (file_) std::fclose(file_);
    if (!committed_) std::remove(temp_.c_str());
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
