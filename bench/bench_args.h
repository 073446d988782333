#pragma once
/// Command-line handling shared by the benchmarks (bench/*.cpp, bench/gl/bench_glsl.cpp): CLI11
/// parsing with the exit statuses the benchmarks have always used, and the default project.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

#include "core/util/data_dir.h"

namespace rrf::bench {

/// Parses argv into the options bound to `app` and returns when the benchmark should run; otherwise
/// exits the process: status 0 after --help, 2 after a usage error (CLI11 prints the message).
inline void parseArgs(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        std::exit(app.exit(e) == 0 ? 0 : 2);
    }
}

/// `given`, or when it is empty the bundled Cornell box of the data directory (core/util/data_dir.h).
/// Exits with status 1 and the places looked in when there is no data directory.
inline std::string projectOrDefault(const std::string& given, const char* program) {
    if (!given.empty()) return given;
    try {
        return bundledProject(kDefaultProject).string();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        std::exit(1);
    }
}

/// Check for a positive integer option (CLI::PositiveNumber's message names the double range).
inline const CLI::Range kPositive{1, std::numeric_limits<int>::max()};

/// Help text of a project option whose default is the bundled Cornell box.
inline constexpr const char* kProjectHelp = "project or scene file (default: the bundled Cornell box)";

}  // namespace rrf::bench
