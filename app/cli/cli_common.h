#pragma once
/// Shared pieces of the rrf subcommands: Ctrl-C handling, thread limits, option parsing and a
/// progress line with ETA on stderr.

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include "core/util/text_format.h"
#include "core/util/vec3.h"

namespace rrf::cli {

/// Installs a SIGINT/SIGTERM handler that sets the returned flag (a second Ctrl-C kills at once).
std::atomic<bool>& installInterruptHandler();

/// Limits oneTBB to `threads` worker threads for the lifetime of the returned object (0 = all cores).
std::unique_ptr<tbb::global_control> limitThreads(int threads);

/// Parses "x,y,z" into a Vec3; throws rrf::InputError naming `option` if malformed or not finite.
Vec3 parseVec3(const std::string& text, const std::string& option);

/// Runs `work` on a worker thread while the calling thread reports progress every 200 ms and turns
/// Ctrl-C into `cancel()`. `progress` returns the fraction done in [0,1] and a short status text.
/// Exceptions thrown by `work` are rethrown here.
void runWithProgress(const std::string& label, const std::function<void()>& work,
                     const std::function<std::pair<double, std::string>()>& progress,
                     const std::function<void()>& cancel);

}  // namespace rrf::cli
