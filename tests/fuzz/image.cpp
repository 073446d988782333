// libFuzzer target: the image reader (readImage: EXR through tinyexr, PFM through the project's own
// parser, PNG/JPEG/HDR/BMP/... through stb_image; the format chosen by the file's magic bytes), fed
// through a file as the programs read references and images. An image it accepts must hold
// width x height RGB pixels. Hostile bytes may be refused with an InputError (a declared size beyond
// the memory budget) or the reader's documented std::runtime_error naming the file
// (tests/fuzz/fuzz_input.h).
//
// The memory budget (core/util/memory_budget.h) reads a MemAvailable of 1 GiB from a scratch
// /proc/meminfo: image headers declare sizes that their compressed data need not back, and the
// decoders' allocations must stay below libFuzzer's 2 GB limit (-rss_limit_mb) whatever memory the
// machine running the fuzzer has, so that only a real leak or an unchecked size is a finding.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/util/image_io.h"
#include "core/util/memory_budget.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    const std::string root = rrf::fuzz::scratchDir() + "/memory-root";
    std::filesystem::create_directories(root + "/proc");
    std::ofstream(root + "/proc/meminfo") << "MemTotal:       2097152 kB\nMemAvailable:   1048576 kB\n";
    rrf::setMemoryInfoRoot(root);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = rrf::fuzz::writeInput("input.img", data, size);
    rrf::fuzz::expectOnlyInputErrors(
        [&] {
            const rrf::Image image = rrf::readImage(path);
            if (image.width <= 0 || image.height <= 0 || image.data.size() != 3 * image.pixelCount())
                rrf::fuzz::finding("an inconsistent image", "size and data disagree");
        },
        // The reader's documented refusal: a std::runtime_error whose message starts with the file.
        [&](const std::exception& e) {
            return dynamic_cast<const std::runtime_error*>(&e) && std::string(e.what()).rfind(path + ":", 0) == 0;
        });
    return 0;
}
