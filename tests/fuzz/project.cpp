// libFuzzer target: the project reader (loadProjectOrScene), fed through a file as the programs
// read it. The scratch directory also holds the bundled Cornell box scene.json and the test OBJ
// files, so a project that names "scene.json" (the bundled one does) loads a real scene and goes
// on to its settings sections. Only an InputError may come out (tests/fuzz/fuzz_input.h).
#include <cstddef>
#include <cstdint>

#include "core/project/project.h"
#include "core/project/project_file.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    rrf::fuzz::provideSourceFile("projects/cornell-box/scene.json", "scene.json");
    rrf::fuzz::provideSourceFile("tests/data/pyramid.obj", "pyramid.obj");
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = rrf::fuzz::writeInput("project.json", data, size);
    rrf::fuzz::expectOnlyInputErrors([&] {
        const rrf::Project project = rrf::loadProjectOrScene(path);
        (void)project;
    });
    return 0;
}
