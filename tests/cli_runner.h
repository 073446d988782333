#pragma once
/// Runs the `rrf` binary (RRF_CLI_PATH, set by CMake on rrf_tests) the way a user would and captures
/// its exit status and output, for the CLI tests.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace rrf::test {

struct CliResult {
    int code = -1;
    std::string output;  ///< stdout and stderr together
};

/// Runs `rrf <args>` through the shell (args are not quoted: callers pass plain paths and flags).
inline CliResult runCli(const std::string& args) {
    CliResult r;
    const std::string cmd = std::string(RRF_CLI_PATH) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace rrf::test
