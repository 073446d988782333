// Image bytes the decoders must not be given (issue 31's image fuzz target): headers that declare
// more pixels than the memory budget holds (a PNG or EXR of a few hundred bytes may declare 16384 x
// 16384 pixels, which stb_image and tinyexr allocate before they read any data), refused with an
// InputError naming the file and the estimate under a budget of 64 MiB read from a fake /proc
// (core/util/memory_budget.h's root); and the inputs that reach stb_image 2.27's known bugs
// (core/util/stb_reader.h: the fuzzer's findings, kept in tests/fuzz/regressions/image/),
// refused naming the file, while the valid images of the fuzz corpus still read.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "core/util/error.h"
#include "core/util/image_io.h"
#include "core/util/memory_budget.h"
#include "tests/test_dirs.h"

namespace test_image_decode_limits {

using namespace rrf;
using namespace rrf::test;
namespace fs = std::filesystem;

namespace {

/// A temp dir whose fake /proc says 64 MiB are available, made the budget's root for the test.
struct SmallMachine {
    fs::path dir;
    SmallMachine() {
        dir = freshTestDir("rrf_decode");
        fs::create_directories(dir / "root/proc");
        std::ofstream(dir / "root/proc/meminfo") << "MemAvailable:   65536 kB\n";
        setMemoryInfoRoot((dir / "root").string());
    }
    ~SmallMachine() {
        setMemoryInfoRoot("");
        fs::remove_all(dir);
    }
    std::string write(const std::string& name, const std::string& bytes) const {
        const fs::path p = dir / name;
        std::ofstream(p, std::ios::binary) << bytes;
        return p.string();
    }
};

void putBigEndian(std::string& s, size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) s[at + size_t(i)] = char((v >> (24 - 8 * i)) & 0xff);
}

/// A PNG signature and IHDR declaring `w` x `h` 8-bit RGB pixels, then `padding` bytes of an
/// ancillary chunk (enough bytes to encode that many pixels, as far as the size check can tell) and
/// IEND: no pixel data at all.
std::string pngHeaderOnly(uint32_t w, uint32_t h, uint32_t padding = 0) {
    std::string png("\x89PNG\r\n\x1a\n", 8);
    std::string ihdr(4 + 4 + 13 + 4, '\0');
    putBigEndian(ihdr, 0, 13);
    std::memcpy(&ihdr[4], "IHDR", 4);
    putBigEndian(ihdr, 8, w);
    putBigEndian(ihdr, 12, h);
    ihdr[16] = 8;  // bit depth
    ihdr[17] = 2;  // colour type: RGB
    std::string text(4 + 4 + padding + 4, ' ');
    putBigEndian(text, 0, padding);
    std::memcpy(&text[4], "tEXt", 4);
    std::string iend(12, '\0');
    std::memcpy(&iend[4], "IEND", 4);
    return png + ihdr + (padding ? text : "") + iend;
}

/// A valid 4 x 4 EXR whose dataWindow is then widened to `side` x `side` (the pixel data stays 4 x 4).
std::string exrDeclaring(int32_t side) {
    std::string exr = encodeImage(Image(4, 4), ImageFormat::EXR);
    const std::string attr("dataWindow\0box2i\0", 17);
    const size_t at = exr.find(attr);
    if (at == std::string::npos) return "";
    const int32_t box[4] = {0, 0, side - 1, side - 1};
    std::memcpy(&exr[at + attr.size() + 4], box, sizeof box);  // after the attribute's size field
    return exr;
}

std::string readError(const std::string& path) {
    try {
        readImage(path);
    } catch (const InputError& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("not an InputError: ") + e.what();
    }
    return "";
}

}  // namespace

TEST(ImageDecodeLimits, PngDeclaringMorePixelsThanMemoryIsRefusedBeforeDecoding) {
    const SmallMachine m;
    // 40 000 bytes could hold 330 M pixels of a 1-bit PNG: the size check lets it through to the budget.
    const std::string png = m.write("huge.png", pngHeaderOnly(16384, 16384, 40000));
    const std::string e = readError(png);
    EXPECT_TRUE(contains(e, png + ": needs about 9.0 GiB of memory (decoding 16384 x 16384 pixels x 36 bytes), but only 64 MiB"))
        << e;
    // A size the budget holds reaches the decoder, which says what is wrong with the data.
    const std::string small = m.write("small.png", pngHeaderOnly(64, 64));
    const std::string e2 = readError(small);
    EXPECT_TRUE(contains(e2, small + ": ")) << e2;
    EXPECT_FALSE(contains(e2, "needs about")) << e2;
    // Without the padding, 45 bytes cannot encode 16384 x 16384 pixels in any PNG.
    const std::string bare = m.write("bare.png", pngHeaderOnly(16384, 16384));
    const std::string e3 = readError(bare);
    EXPECT_TRUE(contains(e3, bare + ": PNG declares 16384 x 16384 pixels, more than its 45 bytes can encode")) << e3;
}

TEST(ImageDecodeLimits, ExrDeclaringMorePixelsThanMemoryIsRefusedBeforeDecoding) {
    const SmallMachine m;
    const std::string bytes = exrDeclaring(16384);
    ASSERT_FALSE(bytes.empty()) << "no dataWindow attribute in the encoder's header";
    const std::string exr = m.write("huge.exr", bytes);
    const std::string e = readError(exr);
    EXPECT_TRUE(contains(e, exr + ": needs about")) << e;
    EXPECT_TRUE(contains(e, "(decoding 16384 x 16384 pixels x 24 bytes), but only 64 MiB")) << e;
    // The unpatched image still reads.
    const std::string ok = m.write("ok.exr", exrDeclaring(4));
    const Image img = readImage(ok);
    EXPECT_EQ(img.width, 4);
    EXPECT_EQ(img.height, 4);
}

TEST(ImageDecodeLimits, InputsReachingStbBugsAreRefusedAndValidImagesRead) {
    const std::string fuzz = std::string(RRF_SOURCE_DIR) + "/tests/fuzz/";
    const struct {
        std::string file, message;
    } refused[] = {
        {"regressions/image/jpeg-huffman-table-of-407-codes.jpg",
         "JPEG Huffman table holds 407 codes, at most 256 are possible (corrupt file)"},
        {"regressions/image/hdr-run-of-length-0.hdr", "HDR scanline 1 holds a run of length 0 (corrupt or truncated file)"},
        {"regressions/image/hdr-without-pixels.hdr", "image has no pixels ("},
        {"regressions/image/bmp-of-width-0.bmp", "image has no pixels (0x3)"},
        {"regressions/image/png-empty-first-idat.png", "PNG image data begins with an empty IDAT chunk"},
        // A fuzz input whose second IDAT claims 1.3 GB: stb reallocated 2 GiB before reading it.
        {"regressions/image/png-idat-claiming-1.3-gb-in-351-bytes.png",
         "PNG IDAT chunk at byte 80 declares 1315333667 bytes, but only 263 follow"},
        // stb takes FF fill bytes before SOI for a JPEG too, so the Huffman check must.
        {"regressions/image/jpeg-fill-byte-before-soi-huffman-overflow.jpg", "JPEG Huffman table holds 568 codes"},
        {"regressions/image/tga-declaring-28m-pixels-in-45-bytes.tga", "TGA declares 656 x 42793 pixels, more than its 45 bytes"},
    };
    for (const auto& r : refused) {
        try {
            readImage(fuzz + r.file);
            ADD_FAILURE() << r.file << " was decoded";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(fuzz + r.file + ": " + r.message, 0), 0u) << e.what();
        }
    }
    // A Radiance header declaring far more pixels than its bytes can encode (16 per byte at most).
    const SmallMachine m;
    const std::string forged = m.write("forged.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4000 +X 4000\n" + std::string(64, '\x02'));
    const std::string e = readError(forged);
    EXPECT_TRUE(contains(e, forged + ": HDR declares 4000 x 4000 pixels, more than its 115 bytes can encode (at most 16 per byte)"))
        << e;
    // A TGA header of 656 x 42793 pixels in 45 bytes (a fuzz input that took 10 s to decode zeros).
    std::string tga(45, '\0');
    tga[2] = 2;
    tga[12] = char(0x90);
    tga[13] = 0x02;
    tga[14] = 0x29;
    tga[15] = char(0xa7);
    tga[16] = 24;
    const std::string slow = m.write("slow.tga", tga);
    const std::string e2 = readError(slow);
    EXPECT_TRUE(contains(e2, slow + ": TGA declares 656 x 42793 pixels, more than its 45 bytes can encode")) << e2;
    for (const char* valid : {"small.jpg", "wide-rle.hdr", "small.hdr", "rgb16.png", "small.bmp", "small.tga"}) {
        const Image img = readImage(fuzz + "corpus/image/" + valid);
        EXPECT_GT(img.pixelCount(), 0u) << valid;
    }
}

}  // namespace test_image_decode_limits
