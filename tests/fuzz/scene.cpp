// libFuzzer target: the scene file reader (JSON text → validated Scene), fed from memory exactly
// as loadScene() reads a file: parseJsonText, then parseScene. OBJ references resolve against a
// scratch directory holding the test OBJ files, so mutated scenes that keep "file" reach the OBJ
// loader too. Only an InputError may come out (tests/fuzz/fuzz_input.h).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/scene/scene_json.h"
#include "core/util/json_reader.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    rrf::fuzz::provideSourceFile("tests/data/pyramid.obj", "pyramid.obj");
    rrf::fuzz::provideSourceFile("tests/data/degenerate.obj", "degenerate.obj");
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string file = rrf::fuzz::scratchDir() + "/scene.json";
    const std::string text(reinterpret_cast<const char*>(data), size);
    rrf::fuzz::expectOnlyInputErrors([&] {
        const rrf::Scene scene = rrf::parseScene(rrf::parseJsonText(text, file), file, rrf::fuzz::scratchDir());
        (void)scene;
    });
    return 0;
}
