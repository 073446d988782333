#pragma once
/// Shared OpenGL context of rrf_gl_tests (made once in main()) and the rule for when there is none.
///
/// CTest runs this binary inside xvfb-run, so a missing context is a real failure. Only a developer
/// who runs the binary by hand on a machine where no X server can be started may set
/// RRF_GL_TESTS_ALLOW_NO_DISPLAY=1, and then the GL tests report themselves as skipped with the reason.

#include <string>

#include <gtest/gtest.h>

#include "app/gl/gl_context.h"

namespace rrf::test {

/// The context, or null when it could not be made (see glUnavailableReason()).
GlContext* glContext();
/// Why there is no context ("" when there is one).
const std::string& glUnavailableReason();
/// True when RRF_GL_TESTS_ALLOW_NO_DISPLAY=1 turns a missing context into a skip.
bool glSkipAllowed();

}  // namespace rrf::test

/// First statement of every test that needs GL: fails (or, when explicitly allowed, skips) with the
/// reason when there is no context, and makes the shared context current.
#define RRF_REQUIRE_GL()                                                                                  \
    do {                                                                                                  \
        if (!::rrf::test::glContext()) {                                                                  \
            if (::rrf::test::glSkipAllowed())                                                             \
                GTEST_SKIP() << "no OpenGL context (RRF_GL_TESTS_ALLOW_NO_DISPLAY=1): "                   \
                             << ::rrf::test::glUnavailableReason();                                       \
            FAIL() << "no OpenGL 3.3 core context: " << ::rrf::test::glUnavailableReason()               \
                   << "\nRun under xvfb-run (ctest does), or set RRF_GL_TESTS_ALLOW_NO_DISPLAY=1 to skip"; \
        }                                                                                                 \
        ::rrf::test::glContext()->makeCurrent();                                                          \
    } while (0)
