// main() of rrf_gl_tests: makes the one OpenGL context before the tests run (GLFW must be driven from
// the main thread) and reports which driver the results are for.

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <unistd.h>

#include "tests/gl/gl_test_env.h"

namespace rrf::test {

namespace {
std::unique_ptr<GlContext> gContext;
std::string gReason;
}  // namespace

GlContext* glContext() { return gContext.get(); }
const std::string& glUnavailableReason() { return gReason; }
bool glSkipAllowed() {
    const char* v = std::getenv("RRF_GL_TESTS_ALLOW_NO_DISPLAY");
    return v && std::strcmp(v, "1") == 0;
}

}  // namespace rrf::test

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    // GLSL program binaries go to a directory of this run (app/gl/program_binary_cache.h), not the
    // user's cache: the tests see a cold cache and leave nothing behind.
    const std::filesystem::path programs =
        std::filesystem::temp_directory_path() / ("rrf_gl_tests_programs_" + std::to_string(::getpid()));
    ::setenv("RRF_PROGRAM_CACHE", programs.c_str(), 1);
    try {
        rrf::test::gContext = std::make_unique<rrf::GlContext>();
        std::cout << "OpenGL: " << rrf::test::gContext->renderer() << " | " << rrf::test::gContext->version() << "\n";
    } catch (const std::exception& e) {
        rrf::test::gReason = e.what();
        std::cerr << "rrf_gl_tests: no OpenGL context: " << e.what() << "\n"
                  << (rrf::test::glSkipAllowed() ? "GL tests will be SKIPPED (RRF_GL_TESTS_ALLOW_NO_DISPLAY=1)\n"
                                                 : "GL tests will FAIL (run under xvfb-run)\n");
    }
    const int rc = RUN_ALL_TESTS();
    rrf::test::gContext.reset();
    std::error_code ec;
    std::filesystem::remove_all(programs, ec);
    return rc;
}
