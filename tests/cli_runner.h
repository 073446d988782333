#pragma once
/// Runs the `rrf` binary (RRF_CLI_PATH, set by CMake on rrf_tests) the way a user would and captures
/// its exit status and output, for the CLI tests.

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace rrf::test {

struct CliResult {
    int code = -1;
    std::string output;  ///< stdout and stderr together
};

/// Runs the shell command `cmd` (stderr should be redirected into stdout by the caller) and returns
/// its exit status (-1 when it did not exit normally) and output.
inline CliResult runShell(const std::string& cmd) {
    CliResult r;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

/// Runs `rrf <args>` through the shell (args are not quoted: callers pass plain paths and flags).
inline CliResult runCli(const std::string& args) { return runShell(std::string(RRF_CLI_PATH) + " " + args + " 2>&1"); }

/// What an interrupted `rrf` run did (interruptCli).
struct InterruptedRun {
    bool started = false;   ///< fork and pipe worked
    bool exited = false;    ///< it ended by itself within a minute of the signal (else it was killed)
    int status = 0;         ///< waitpid status
    std::string err;        ///< its stderr
    double seconds = 0;     ///< from the signal to its end
};

/// Runs `rrf <args>` (stdout to /dev/null), waits until its stderr shows `ready` (the progress line:
/// the interrupt handler is installed and the work under way), sends SIGINT and reads its stderr until
/// it exits; a process still running a minute after the signal is killed (exited = false).
inline InterruptedRun interruptCli(const std::vector<std::string>& args, const std::string& ready) {
    InterruptedRun r;
    int fds[2];
    if (::pipe(fds) != 0) return r;
    std::vector<char*> argv{const_cast<char*>("rrf")};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) return r;
    if (pid == 0) {
        ::dup2(fds[1], 2);
        ::close(fds[0]);
        const int devNull = ::open("/dev/null", O_WRONLY);
        ::dup2(devNull, 1);
        ::execv(RRF_CLI_PATH, argv.data());
        ::_exit(127);
    }
    r.started = true;
    ::close(fds[1]);
    char buf[256];
    ssize_t n;
    while (r.err.find(ready) == std::string::npos && (n = ::read(fds[0], buf, sizeof buf)) > 0) r.err.append(buf, size_t(n));
    const auto signalled = std::chrono::steady_clock::now();
    ::kill(pid, SIGINT);
    const auto deadline = signalled + std::chrono::seconds(60);
    ::fcntl(fds[0], F_SETFL, O_NONBLOCK);
    pid_t ended = 0;
    while ((ended = ::waitpid(pid, &r.status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < deadline) {
        while ((n = ::read(fds[0], buf, sizeof buf)) > 0) r.err.append(buf, size_t(n));
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
    if (ended == 0) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &r.status, 0);
    } else {
        r.exited = ended == pid;
    }
    while ((n = ::read(fds[0], buf, sizeof buf)) > 0) r.err.append(buf, size_t(n));
    ::close(fds[0]);
    return r;
}

}  // namespace rrf::test
