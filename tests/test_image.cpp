#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include <tinyexr.h>
#include <unistd.h>

#include "core/util/atomic_file.h"
#include "core/util/image.h"
#include "core/util/image_io.h"

namespace test_image {

namespace fs = std::filesystem;
using namespace rrf;

namespace {

/// A fresh directory per test, removed afterwards, so leftover files are easy to detect.
struct TempDir {
    fs::path dir;
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() /
              ("rrf_image_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~TempDir() { fs::remove_all(dir); }
    std::string file(const std::string& name) const { return (dir / name).string(); }
    size_t entries() const { return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator())); }
};

/// 5×3, every pixel different, with values that exercise the float format (negative, denormal,
/// huge, tiny), so any flip, transpose or conversion shows.
Image asymmetricImage() {
    Image img(5, 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            img.set(x, y, {float(x) + 10.f * float(y), -0.1f * float(x + 1) * float(y + 1), std::ldexp(1.3f, x * 7 - 20 + y)});
    img.set(4, 0, {1e-40f, 3.4e38f, 1.17549435e-38f});
    return img;
}

void expectBitExact(const Image& a, const Image& b) {
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    ASSERT_EQ(a.data.size(), b.data.size());
    EXPECT_EQ(0, std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)));
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "<no exception>";
}

std::string leBytes(float v) {
    uint32_t b;
    std::memcpy(&b, &v, 4);
    return {char(b & 0xff), char((b >> 8) & 0xff), char((b >> 16) & 0xff), char(b >> 24)};
}

int pngByte(float linear) { return int(std::lround(linearToSrgb(linear) * 255.f)); }

}  // namespace

TEST(Image, ConstructSetAtMean) {
    Image img(2, 2, Vec3(1.f, 2.f, 3.f));
    EXPECT_EQ(img.data.size(), 12u);
    img.set(1, 0, {5.f, 6.f, 7.f});
    EXPECT_EQ(img.at(1, 0), Vec3(5.f, 6.f, 7.f));
    EXPECT_EQ(img.data[3], 5.f);  // row-major, top row first
    EXPECT_EQ(img.mean(), Vec3(2.f, 3.f, 4.f));
    EXPECT_THROW(Image(-1, 2), std::invalid_argument);
}

TEST(Image, CountsNonFinitePixels) {
    Image img(3, 1);
    EXPECT_EQ(img.nonFiniteCount(), 0u);
    img.set(0, 0, {std::numeric_limits<float>::quiet_NaN(), 0.f, 0.f});
    img.set(2, 0, {0.f, 0.f, -std::numeric_limits<float>::infinity()});
    EXPECT_EQ(img.nonFiniteCount(), 2u);
    EXPECT_FALSE(img.mean().isFinite());
}

TEST(Image, LuminanceIsRec709) {
    EXPECT_NEAR(luminance(Vec3(1.f)), 1.f, 1e-6f);
    EXPECT_FLOAT_EQ(luminance({1.f, 0.f, 0.f}), 0.2126f);
    EXPECT_FLOAT_EQ(luminance({0.f, 1.f, 0.f}), 0.7152f);
    EXPECT_FLOAT_EQ(luminance({0.f, 0.f, 1.f}), 0.0722f);
}

TEST(Image, FormatFromNameAndPath) {
    EXPECT_EQ(imageFormatFromName("exr"), ImageFormat::EXR);
    EXPECT_EQ(imageFormatFromName("PFM"), ImageFormat::PFM);
    EXPECT_EQ(imageFormatFromPath("out/a.b/render.png"), ImageFormat::PNG);
    try {
        imageFormatFromName("jpg");
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("exr, pfm, png"), std::string::npos) << e.what();
    }
    EXPECT_THROW(imageFormatFromPath("dir.exr/noext"), std::invalid_argument);
}

TEST(Image, ExrRoundTripIsBitExact) {
    TempDir tmp;
    const Image img = asymmetricImage();
    writeImage(tmp.file("a.exr"), img, ImageFormat::EXR);
    expectBitExact(img, readImage(tmp.file("a.exr")));
}

TEST(Image, PfmRoundTripIsBitExactAndBottomRowFirst) {
    TempDir tmp;
    const Image img = asymmetricImage();
    writeImage(tmp.file("a.pfm"), img, ImageFormat::PFM);
    expectBitExact(img, readImage(tmp.file("a.pfm")));

    const std::string bytes = readFile(tmp.file("a.pfm"));
    const std::string header = "PF\n5 3\n-1.0\n";
    ASSERT_EQ(bytes.substr(0, header.size()), header);
    ASSERT_EQ(bytes.size(), header.size() + 5 * 3 * 12);
    // The first stored pixel is the bottom-left one, little-endian.
    EXPECT_EQ(bytes.substr(header.size(), 4), leBytes(img.at(0, 2).x));
}

TEST(Image, PfmReadsBigEndianAndGreyscale) {
    TempDir tmp;
    // 2×1 greyscale, big-endian (positive scale): values 0.5 (left) and -2 (right).
    std::string be = "Pf\n2 1\n1.0\n";
    for (float v : {0.5f, -2.f}) {
        const std::string le = leBytes(v);
        be += std::string(le.rbegin(), le.rend());
    }
    std::ofstream(tmp.file("grey.pfm"), std::ios::binary) << be;
    const Image img = readImage(tmp.file("grey.pfm"));
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 1);
    EXPECT_EQ(img.at(0, 0), Vec3(0.5f));
    EXPECT_EQ(img.at(1, 0), Vec3(-2.f));
}

TEST(Image, PngRoundTripWithinOneStep) {
    TempDir tmp;
    Image img(16, 4);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            img.set(x, y, {float(x) / 15.f, float(y) / 3.f, float(x * y) / 45.f});
    writeImage(tmp.file("a.png"), img, ImageFormat::PNG);
    const Image back = readImage(tmp.file("a.png"));
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    for (size_t i = 0; i < img.data.size(); ++i)
        EXPECT_NEAR(linearToSrgb(back.data[i]), linearToSrgb(img.data[i]), 0.5f / 255.f + 1e-6f) << i;
}

TEST(Image, PngUsesExactSrgbCurve) {
    TempDir tmp;
    const float values[] = {0.f, 1.f, 0.5f, 0.0031308f, 2.f, -1.f};
    const int expected[] = {0, 255, 188, 10, 255, 0};
    Image img(6, 1);
    for (int x = 0; x < 6; ++x) img.set(x, 0, Vec3(values[x]));
    writeImage(tmp.file("curve.png"), img, ImageFormat::PNG);
    const Image back = readImage(tmp.file("curve.png"));
    for (int x = 0; x < 6; ++x) {
        EXPECT_EQ(pngByte(back.at(x, 0).x), expected[x]) << "input " << values[x];
        EXPECT_EQ(back.at(x, 0).x, back.at(x, 0).z);
    }
    // The two branches of the curve meet at the breakpoint.
    EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-6f);
    EXPECT_NEAR(srgbToLinear(linearToSrgb(0.5f)), 0.5f, 1e-6f);
}

TEST(Image, PngExposureDoubles) {
    const Image quarter(3, 2, Vec3(0.25f, 0.1f, 0.4f));
    const Image half(3, 2, Vec3(0.5f, 0.2f, 0.8f));
    EXPECT_EQ(encodeImage(quarter, ImageFormat::PNG, 1.f), encodeImage(half, ImageFormat::PNG, 0.f));
    EXPECT_NE(encodeImage(quarter, ImageFormat::PNG, 0.f), encodeImage(half, ImageFormat::PNG, 0.f));
    // HDR formats store radiance, not a picture: exposure leaves them alone.
    EXPECT_EQ(encodeImage(quarter, ImageFormat::PFM, 3.f), encodeImage(quarter, ImageFormat::PFM, 0.f));
    EXPECT_THROW(encodeImage(quarter, ImageFormat::PNG, NAN), std::invalid_argument);
}

TEST(Image, WriteRefusesNonFiniteAndLeavesNoFile) {
    TempDir tmp;
    Image img(4, 4, Vec3(0.5f));
    img.set(1, 1, {std::numeric_limits<float>::quiet_NaN(), 0.f, 0.f});
    img.set(3, 2, {0.f, std::numeric_limits<float>::infinity(), 0.f});
    for (ImageFormat f : {ImageFormat::EXR, ImageFormat::PFM, ImageFormat::PNG}) {
        const std::string path = tmp.file(std::string("bad.") + imageFormatName(f));
        const std::string msg = errorOf([&] { writeImage(path, img, f); });
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        EXPECT_NE(msg.find("2 NaN/Inf pixels"), std::string::npos) << msg;
    }
    EXPECT_EQ(tmp.entries(), 0u);
    EXPECT_NE(errorOf([&] { writeImage(tmp.file("empty.exr"), Image(), ImageFormat::EXR); }).find("empty"),
              std::string::npos);
}

TEST(Image, TruncatedPfmNamesFile) {
    TempDir tmp;
    writeImage(tmp.file("t.pfm"), asymmetricImage(), ImageFormat::PFM);
    std::string bytes = readFile(tmp.file("t.pfm"));
    bytes.resize(bytes.size() - 7);
    std::ofstream(tmp.file("t.pfm"), std::ios::binary | std::ios::trunc) << bytes;
    const std::string msg = errorOf([&] { readImage(tmp.file("t.pfm")); });
    EXPECT_NE(msg.find(tmp.file("t.pfm")), std::string::npos) << msg;
    EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;

    // A header cut short, and absurd dimensions, fail before anything large is allocated.
    std::ofstream(tmp.file("h.pfm"), std::ios::binary | std::ios::trunc) << "PF\n5 3";
    EXPECT_NE(errorOf([&] { readImage(tmp.file("h.pfm")); }).find(tmp.file("h.pfm")), std::string::npos);
    std::ofstream(tmp.file("huge.pfm"), std::ios::binary | std::ios::trunc) << "PF\n2000000000 2000000000\n-1.0\n1234";
    EXPECT_NE(errorOf([&] { readImage(tmp.file("huge.pfm")); }).find("truncated"), std::string::npos);
    std::ofstream(tmp.file("neg.pfm"), std::ios::binary | std::ios::trunc) << "PF\n-5 3\n-1.0\n";
    EXPECT_NE(errorOf([&] { readImage(tmp.file("neg.pfm")); }).find("width"), std::string::npos);
}

TEST(Image, TruncatedExrNamesFile) {
    TempDir tmp;
    writeImage(tmp.file("t.exr"), asymmetricImage(), ImageFormat::EXR);
    const std::string full = readFile(tmp.file("t.exr"));
    for (size_t keep : {full.size() - 9, full.size() / 2, size_t(40), size_t(6)}) {
        std::ofstream(tmp.file("t.exr"), std::ios::binary | std::ios::trunc) << full.substr(0, keep);
        const std::string msg = errorOf([&] { readImage(tmp.file("t.exr")); });
        EXPECT_EQ(msg.rfind(tmp.file("t.exr"), 0), 0u) << "kept " << keep << ": " << msg;
    }
}

TEST(Image, WrongMagicNamesFile) {
    TempDir tmp;
    std::ofstream(tmp.file("m.pfm"), std::ios::binary) << "PX\n5 3\n-1.0\n0123456789";
    std::string msg = errorOf([&] { readImage(tmp.file("m.pfm")); });
    EXPECT_NE(msg.find(tmp.file("m.pfm")), std::string::npos) << msg;
    EXPECT_NE(msg.find("magic"), std::string::npos) << msg;

    std::ofstream(tmp.file("m.exr"), std::ios::binary) << "not an exr file at all";
    msg = errorOf([&] { readImage(tmp.file("m.exr")); });
    EXPECT_NE(msg.find(tmp.file("m.exr")), std::string::npos) << msg;

    std::ofstream(tmp.file("m.dat"), std::ios::binary) << "garbage garbage garbage";
    msg = errorOf([&] { readImage(tmp.file("m.dat")); });
    EXPECT_NE(msg.find(tmp.file("m.dat")), std::string::npos) << msg;

    std::ofstream(tmp.file("zero.png"), std::ios::binary);
    EXPECT_NE(errorOf([&] { readImage(tmp.file("zero.png")); }).find("empty"), std::string::npos);
    EXPECT_NE(errorOf([&] { readImage(tmp.file("missing.exr")); }).find(tmp.file("missing.exr")), std::string::npos);
}

TEST(Image, ExrReadsHalfLayeredChannels) {
    // 2×1 half-float file with an alpha channel and layer-prefixed colour channels, as compositors
    // write them; values are exactly representable in half precision.
    TempDir tmp;
    const char* names[4] = {"A", "beauty.B", "beauty.G", "beauty.R"};
    float planes[4][2] = {{1.f, 1.f}, {0.25f, 4.f}, {0.5f, 2.f}, {1.5f, -8.f}};
    float* ptrs[4] = {planes[0], planes[1], planes[2], planes[3]};
    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = 4;
    image.images = reinterpret_cast<unsigned char**>(ptrs);
    image.width = 2;
    image.height = 1;
    EXRHeader header;
    InitEXRHeader(&header);
    EXRChannelInfo channels[4] = {};
    int types[4], requested[4];
    for (int c = 0; c < 4; ++c) {
        std::strncpy(channels[c].name, names[c], 255);
        types[c] = TINYEXR_PIXELTYPE_FLOAT;
        requested[c] = TINYEXR_PIXELTYPE_HALF;
    }
    header.num_channels = 4;
    header.channels = channels;
    header.pixel_types = types;
    header.requested_pixel_types = requested;
    unsigned char* mem = nullptr;
    const char* err = nullptr;
    const size_t n = SaveEXRImageToMemory(&image, &header, &mem, &err);
    ASSERT_GT(n, 0u) << (err ? err : "");
    writeFileAtomically(tmp.file("half.exr"), std::string(reinterpret_cast<char*>(mem), n));
    std::free(mem);

    const Image img = readImage(tmp.file("half.exr"));
    ASSERT_EQ(img.width, 2);
    EXPECT_EQ(img.at(0, 0), Vec3(1.5f, 0.5f, 0.25f));
    EXPECT_EQ(img.at(1, 0), Vec3(-8.f, 2.f, 4.f));
}

TEST(Image, FalseColorEndpoints) {
    Image s(5, 1);
    const float v[5] = {-1.f, 0.f, 1.f, 2.f, std::numeric_limits<float>::quiet_NaN()};
    for (int x = 0; x < 5; ++x) s.set(x, 0, {v[x], 123.f, -5.f});
    const Image c = falseColor(s, 0.f, 1.f);
    const Vec3 bottom(srgbToLinear(0.267004f), srgbToLinear(0.004874f), srgbToLinear(0.329415f));
    const Vec3 top(srgbToLinear(0.993248f), srgbToLinear(0.906157f), srgbToLinear(0.143936f));
    for (int ch = 0; ch < 3; ++ch) {
        EXPECT_FLOAT_EQ(c.at(0, 0)[ch], bottom[ch]);  // below lo clamps
        EXPECT_FLOAT_EQ(c.at(1, 0)[ch], bottom[ch]);
        EXPECT_FLOAT_EQ(c.at(2, 0)[ch], top[ch]);
        EXPECT_FLOAT_EQ(c.at(3, 0)[ch], top[ch]);  // above hi clamps
    }
    EXPECT_EQ(c.at(4, 0), Vec3(1.f, 0.f, 1.f));  // NaN stays visible
    // Viridis rises monotonically in luminance, which is what makes it readable as a scale.
    float prev = -1.f;
    for (int i = 0; i <= 100; ++i) {
        const float l = luminance(viridis(float(i) / 100.f));
        EXPECT_GT(l, prev) << i;
        prev = l;
    }
    EXPECT_THROW(falseColor(s, 1.f, 0.f), std::invalid_argument);
    EXPECT_EQ(falseColor(s, 0.5f, 0.5f).at(2, 0), viridis(1.f));
}

}  // namespace test_image
