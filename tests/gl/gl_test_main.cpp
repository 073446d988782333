// main() of rrf_gl_tests: makes the one OpenGL context before the tests run (GLFW must be driven from
// the main thread) and reports which driver the results are for.

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>

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
    return rc;
}
