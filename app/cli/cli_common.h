#pragma once
/// Shared pieces of the rrf subcommands: Ctrl-C handling, thread limits, a progress line with ETA on
/// stderr, output files and the one place where core's setting names become flags in error messages.

#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "core/scene/scene.h"
#include "core/util/text_format.h"

namespace rrf {
struct Project;
}

namespace rrf::cli {

/// Installs a SIGINT/SIGTERM handler that sets the returned flag (a second Ctrl-C kills at once).
std::atomic<bool>& installInterruptHandler();

/// Limits oneTBB to `threads` worker threads for the lifetime of the returned object (0 = all cores).
std::unique_ptr<tbb::global_control> limitThreads(int threads);

/// Throws InputError("command line", `flag`, ...) unless the movable light of `scene` placed with its
/// centre at `p` stays in the coordinate range where rays are valid (core/scene/coordinate_range.h).
void checkLightPosition(const Scene& scene, const Vec3& p, const std::string& flag = "--light-pos");

/// Throws InputError("command line", `flag`, ...) when `output` is the same file or directory as
/// one of `inputs` (compared by device and inode, so another spelling or a link of the same file
/// counts): a command must never replace the file it reads. Paths that do not exist yet cannot be.
void refuseOverwritingInputs(const std::string& output, const std::vector<std::string>& inputs,
                             const std::string& flag = "--out");

/// The files a loaded project was read from: its own file and, when it names a separate scene file,
/// that file (an output must not replace either).
std::vector<std::string> projectInputs(const Project& project);

/// `dir`/`name` as a path string.
std::string outputPath(const std::string& dir, const std::string& name);

/// Writes `text` to `file` atomically and prints "wrote <file>".
void writeReported(const std::string& file, const std::string& text);

/// The message `rrf` prints for an error: a SettingError names the flag that sets the setting
/// ("sweep values" → "command line: --values: ..."), anything else its own message.
std::string errorMessage(const std::exception& e);

/// Runs `work` on a worker thread while the calling thread reports progress every 200 ms and turns
/// Ctrl-C into `cancel()`. `progress` returns the fraction done in [0,1] and a short status text.
/// Exceptions thrown by `work` are rethrown here.
void runWithProgress(const std::string& label, const std::function<void()>& work,
                     const std::function<std::pair<double, std::string>()>& progress,
                     const std::function<void()>& cancel);

}  // namespace rrf::cli
