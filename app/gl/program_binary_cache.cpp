// ProgramBinaryCache (program_binary_cache.h): linked programs' binaries on disk, keyed by sources and driver.
#include "app/gl/program_binary_cache.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <glad/gl.h>

#include "core/data/dataset_file.h"  // checksum64
#include "core/util/atomic_file.h"

namespace rrf {

namespace fs = std::filesystem;

namespace {

/// File layout: magic, binary format (GLenum), binary bytes, checksum64 of the binary, the binary.
constexpr char kMagic[8] = {'R', 'R', 'F', 'P', 'R', 'O', 'G', '1'};
constexpr size_t kHeader = 8 + 4 + 8 + 8;

std::string driverString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}

/// Appends `s` with its length, so that no two different source pairs give the same bytes.
void appendField(std::string& out, const std::string& s) {
    const uint64_t n = s.size();
    out.append(reinterpret_cast<const char*>(&n), sizeof n);
    out += s;
}

}  // namespace

ProgramBinaryCache::ProgramBinaryCache(std::string dir) : dir_(std::move(dir)) {}

std::string ProgramBinaryCache::defaultDirectory() {
    if (const char* own = std::getenv("RRF_PROGRAM_CACHE")) return own;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "rrf" / "programs").string();
    if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "rrf" / "programs").string();
    return "";
}

namespace {
/// What the cache did for the calling thread (countsOnThisThread).
thread_local ProgramBinaryCache::Counts threadCounts;
}  // namespace

ProgramBinaryCache::Counts ProgramBinaryCache::countsOnThisThread() { return threadCounts; }

ProgramBinaryCache& ProgramBinaryCache::shared() {
    static ProgramBinaryCache cache(defaultDirectory());
    return cache;
}

uint64_t ProgramBinaryCache::key(const std::string& vertexSource, const std::string& fragmentSource) {
    std::string all;
    for (const std::string& s : {vertexSource, fragmentSource, driverString(GL_VENDOR), driverString(GL_RENDERER), driverString(GL_VERSION)})
        appendField(all, s);
    return checksum64(all.data(), all.size());
}

std::string ProgramBinaryCache::fileFor(uint64_t key) const {
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.glprog", static_cast<unsigned long long>(key));
    return (fs::path(dir_) / name).string();
}

void ProgramBinaryCache::note(std::string line) {
    std::lock_guard<std::mutex> lock(mutex_);
    notes_.push_back(std::move(line));
}

std::vector<std::string> ProgramBinaryCache::takeNotes() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> out;
    out.swap(notes_);
    return out;
}

ProgramBinaryCache::Counts ProgramBinaryCache::counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
}

bool ProgramBinaryCache::supported() {
    // Asked by the first GL thread that needs it (the live prediction's worker and a sweep's may
    // both); the others wait for its answer.
    std::call_once(supportedAsked_, [this] {
        GLint formats = 0;
        glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
        glGetError();  // a driver without the query flags an error that is not the caller's
        supported_ = formats > 0;
        if (dir_.empty())
            note("program binary cache off (RRF_PROGRAM_CACHE is empty or no home directory): shaders compile at every start");
        else if (!supported_)
            note("program binary cache unused: the driver (" + driverString(GL_RENDERER) +
                 ") offers no program binary format (GL_NUM_PROGRAM_BINARY_FORMATS 0), so shaders compile at every start");
    });
    return supported_ > 0 && !dir_.empty();
}

bool ProgramBinaryCache::load(uint64_t key, unsigned program) {
    if (!supported()) return false;
    const std::string path = fileFor(key);
    std::error_code ec;
    if (!fs::exists(path, ec)) {
        std::lock_guard<std::mutex> lock(mutex_);
        ++counts_.misses;
        ++threadCounts.misses;
        return false;
    }
    auto refuse = [&](const std::string& why) {
        note("program cache: " + path + ": " + why + "; compiling the shaders instead");
        std::lock_guard<std::mutex> lock(mutex_);
        ++counts_.refused;
        ++threadCounts.refused;
        ++counts_.misses;
        ++threadCounts.misses;
        return false;
    };
    std::string bytes;
    try {
        bytes = readFile(path);
    } catch (const std::exception& e) {
        return refuse(std::string("cannot be read (") + e.what() + ")");
    }
    if (bytes.size() < kHeader || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        return refuse("not a program binary of this workbench (bad header)");
    uint32_t format = 0;
    uint64_t length = 0, sum = 0;
    std::memcpy(&format, bytes.data() + 8, 4);
    std::memcpy(&length, bytes.data() + 12, 8);
    std::memcpy(&sum, bytes.data() + 20, 8);
    if (length != bytes.size() - kHeader) return refuse("truncated or padded (length does not match)");
    if (checksum64(bytes.data() + kHeader, length) != sum) return refuse("damaged (checksum mismatch)");
    glProgramBinary(program, GLenum(format), bytes.data() + kHeader, GLsizei(length));
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    // A rejected binary sets no error that is the caller's; clear what the driver may have flagged
    // (bounded: a lost context keeps reporting an error).
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {}
    if (ok != GL_TRUE) return refuse("refused by the driver (another driver build)");
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.hits;
    ++threadCounts.hits;
    return true;
}

void ProgramBinaryCache::store(uint64_t key, unsigned program) {
    if (!supported()) return;
    GLint length = 0;
    glGetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
    if (length <= 0) return;
    std::string bytes(kHeader + size_t(length), '\0');
    GLenum format = 0;
    GLsizei written = 0;
    glGetProgramBinary(program, length, &written, &format, bytes.data() + kHeader);
    if (glGetError() != GL_NO_ERROR || written <= 0) return;  // best effort: the program itself is fine
    bytes.resize(kHeader + size_t(written));
    const uint32_t f = format;
    const uint64_t n = uint64_t(written), sum = checksum64(bytes.data() + kHeader, size_t(written));
    std::memcpy(bytes.data(), kMagic, 8);
    std::memcpy(bytes.data() + 8, &f, 4);
    std::memcpy(bytes.data() + 12, &n, 8);
    std::memcpy(bytes.data() + 20, &sum, 8);
    try {
        fs::create_directories(dir_);
        writeFileAtomically(fileFor(key), bytes);
    } catch (const std::exception& e) {
        note(std::string("program cache: not stored (the next start compiles again): ") + e.what());
        return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.stored;
    ++threadCounts.stored;
}

}  // namespace rrf
