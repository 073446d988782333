#pragma once
/// Linked shader programs kept on disk between runs (glGetProgramBinary / glProgramBinary), so that
/// reopening a project does not compile and link the prediction shaders again on the UI thread
/// (issue 29: a compile of a 40-10 network's predict.frag is the largest single stall of a reopen).
///
/// A binary is stored under a key of the program's exact sources and the driver's GL_VENDOR,
/// GL_RENDERER and GL_VERSION strings, one file per key in the cache directory
/// ($XDG_CACHE_HOME/rrf/programs, else ~/.cache/rrf/programs; RRF_PROGRAM_CACHE overrides, an empty
/// value turns caching off), written atomically. A file that is damaged, truncated or refused by the
/// driver (a driver update that kept its strings) is a warning naming the file and a miss: the
/// caller compiles, and the fresh binary replaces the file. Drivers without a binary format
/// (GL_NUM_PROGRAM_BINARY_FORMATS 0, as some Mesa builds) make the cache a no-op, said once in a note.
///
/// GL calls need a current context on the calling thread (the GL workers' in the workbench,
/// app/gl/gl_worker.h); several threads may use the shared cache at once. Notes and warnings are
/// collected for the caller's log (takeNotes), since app/gl has no log of its own.

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace rrf {

class ProgramBinaryCache {
public:
    /// A cache in `dir` (created on the first store); empty: disabled.
    explicit ProgramBinaryCache(std::string dir);

    /// The directory named in the header comment ("" when RRF_PROGRAM_CACHE is set and empty, or
    /// no home directory is known).
    static std::string defaultDirectory();
    /// The cache GlProgram uses: in defaultDirectory(), made at the first call.
    static ProgramBinaryCache& shared();

    /// The key of a program of these sources under the current context's driver.
    static uint64_t key(const std::string& vertexSource, const std::string& fragmentSource);
    /// Loads the binary stored for `key` into `program` (a glCreateProgram name with nothing
    /// attached) and returns true when the driver linked it; false on a miss, a disabled or
    /// unsupported cache, or a bad file (a warning note naming the file).
    bool load(uint64_t key, unsigned program);
    /// Stores the binary of linked `program` for `key` (best effort: a failure is a warning note).
    /// The program must have been linked with GL_PROGRAM_BINARY_RETRIEVABLE_HINT set.
    void store(uint64_t key, unsigned program);
    /// Whether the driver offers a binary format (asks once; needs a current context).
    bool supported();

    /// The file a key is stored in.
    std::string fileFor(uint64_t key) const;
    const std::string& directory() const { return dir_; }

    /// What happened since the last call, for the log: warnings (bad files) and one-time notes.
    std::vector<std::string> takeNotes();
    /// Counts since the cache was made (tests and the log): binaries linked from disk, misses
    /// (compiled), binaries stored, files refused (damaged or rejected by the driver).
    struct Counts {
        int hits = 0, misses = 0, stored = 0, refused = 0;
    };
    Counts counts() const;
    /// The same counts, of what this cache did for the calling thread only (a GL worker's build
    /// while another thread compiles, too).
    static Counts countsOnThisThread();

private:
    void note(std::string line);

    std::string dir_;
    std::once_flag supportedAsked_;
    int supported_ = -1;  ///< -1: not asked yet (written once, under supportedAsked_)
    mutable std::mutex mutex_;  ///< guards notes_ and counts_ (read by other threads in tests)
    std::vector<std::string> notes_;
    Counts counts_;
};

}  // namespace rrf
