// The GLSL program binary cache (app/gl/program_binary_cache.h, issue 29): a program built twice
// from the same sources is linked from its stored binary the second time; a damaged or foreign
// file is refused with a note naming it and the program is compiled instead; a driver without a
// binary format makes the cache a no-op that says so. rrf_gl_tests' main() points the shared
// cache at a private directory (RRF_PROGRAM_CACHE).
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <glad/gl.h>

#include "app/gl/gl_program.h"
#include "app/gl/program_binary_cache.h"
#include "tests/gl/gl_test_env.h"

namespace rrf::test::test_program_binary_cache {

namespace fs = std::filesystem;

namespace {

const char* kVertex = "#version 330 core\nvoid main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n";

/// A fragment shader no other test builds, so its key is this test's own (`tag` varies it).
std::string fragment(const std::string& tag) {
    return "#version 330 core\n// " + tag + "\nout vec4 colour;\nuniform float uValue;\nvoid main() { colour = vec4(uValue); }\n";
}

bool anyNoteContains(const std::vector<std::string>& notes, const std::string& text) {
    for (const std::string& n : notes)
        if (n.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST(ProgramBinaryCache, SecondBuildOfTheSameSourcesIsLinkedFromTheCache) {
    RRF_REQUIRE_GL();
    ProgramBinaryCache& cache = ProgramBinaryCache::shared();
    ASSERT_FALSE(cache.directory().empty()) << "rrf_gl_tests sets RRF_PROGRAM_CACHE";
    const std::string frag = fragment("second build " + std::to_string(::getpid()));
    const ProgramBinaryCache::Counts before = cache.counts();
    GlProgram first("test.vert", kVertex, "test.frag", frag);
    EXPECT_NE(first.id(), 0u);
    if (!cache.supported()) {
        // No binary format: nothing stored, nothing found, and a note says why (once per process).
        EXPECT_EQ(cache.counts().stored, before.stored);
        GlProgram second("test.vert", kVertex, "test.frag", frag);
        EXPECT_NE(second.id(), 0u);
        EXPECT_EQ(cache.counts().hits, before.hits);
        std::printf("  the driver offers no program binary format: the cache is a no-op here\n");
        return;
    }
    EXPECT_EQ(cache.counts().stored, before.stored + 1);
    EXPECT_TRUE(fs::exists(cache.fileFor(ProgramBinaryCache::key(kVertex, frag))));
    GlProgram second("test.vert", kVertex, "test.frag", frag);
    EXPECT_EQ(cache.counts().hits, before.hits + 1);
    // The program from the binary works as the compiled one: its uniform is there.
    EXPECT_GE(second.uniform("uValue"), 0);
}

TEST(ProgramBinaryCache, DamagedFileIsRefusedNamedAndCompiledInstead) {
    RRF_REQUIRE_GL();
    ProgramBinaryCache& cache = ProgramBinaryCache::shared();
    if (!cache.supported()) GTEST_SKIP() << "the driver offers no program binary format";
    cache.takeNotes();
    const std::string frag = fragment("damaged " + std::to_string(::getpid()));
    const std::string file = cache.fileFor(ProgramBinaryCache::key(kVertex, frag));
    { GlProgram built("test.vert", kVertex, "test.frag", frag); }
    ASSERT_TRUE(fs::exists(file));
    for (const std::string& damage : {std::string("short"), std::string("flip"), std::string("foreign")}) {
        std::string bytes;
        {
            std::ifstream in(file, std::ios::binary);
            bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        }
        if (damage == "short") bytes.resize(bytes.size() / 2);
        else if (damage == "flip") bytes[bytes.size() - 1] = char(bytes.back() ^ 0x5a);
        else bytes = "RRFPROG1 not a program at all";
        std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
        const ProgramBinaryCache::Counts before = cache.counts();
        GlProgram rebuilt("test.vert", kVertex, "test.frag", frag);
        EXPECT_NE(rebuilt.id(), 0u) << damage;
        EXPECT_GE(rebuilt.uniform("uValue"), 0) << damage;
        EXPECT_EQ(cache.counts().refused, before.refused + 1) << damage;
        EXPECT_EQ(cache.counts().stored, before.stored + 1) << damage << ": the fresh binary replaces the file";
        EXPECT_TRUE(anyNoteContains(cache.takeNotes(), file)) << damage;
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << damage;
    }
}

}  // namespace rrf::test::test_program_binary_cache
