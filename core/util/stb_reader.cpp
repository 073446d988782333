#include "core/util/stb_reader.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>

// Compiled here only, with internal linkage (see the header for the formats).
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STBI_ONLY_HDR
#define STBI_NO_STDIO
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include "core/util/memory_budget.h"

namespace rrf {

namespace {

/// A read cursor over the bytes that, like stb's memory reader, returns 0 at the end without moving.
struct StbCursor {
    const std::string& bytes;
    size_t pos = 0;
    bool atEnd() const { return pos >= bytes.size(); }
    unsigned get() { return atEnd() ? 0u : static_cast<unsigned char>(bytes[pos++]); }
    unsigned peek(size_t ahead) const {
        return pos + ahead < bytes.size() ? static_cast<unsigned char>(bytes[pos + ahead]) : 0u;
    }
};

/// stbi__hdr_gettoken: a line up to '\n' (not included), at most 1023 characters, the rest of a
/// longer line skipped.
std::string hdrToken(StbCursor& c) {
    std::string token;
    unsigned ch = c.get();
    while (!c.atEnd() && ch != '\n') {
        token += char(ch);
        if (token.size() == 1023) {
            while (!c.atEnd() && c.get() != '\n') {
            }
            break;
        }
        ch = c.get();
    }
    return token;
}

bool stbStartsWith(const std::string& s, const char* prefix) { return s.compare(0, std::strlen(prefix), prefix) == 0; }

[[noreturn]] void stbFail(const std::string& name, const std::string& what) { throw std::runtime_error(name + ": " + what); }

/// stb decodes headers of no pixels (a Radiance "-Y 0 +X 5", a BMP of width 0) into an empty
/// buffer; an Image needs at least one pixel.
void requirePixels(int w, int h, const std::string& name) {
    if (w <= 0 || h <= 0) stbFail(name, "image has no pixels (" + std::to_string(w) + "x" + std::to_string(h) + ")");
}

/// Where a JPEG's markers begin (after SOI), or 0 if `bytes` do not start as stb reads a JPEG: FF,
/// any number of FF fill bytes, D8.
size_t jpegStart(const std::string& bytes) {
    StbCursor c{bytes};
    if (c.get() != 0xFF) return 0;
    unsigned x = c.get();
    while (x == 0xFF && !c.atEnd()) x = c.get();
    return x == 0xD8 ? c.pos : 0;
}

}  // namespace

std::string jpegHuffmanProblem(const std::string& bytes) {
    // Markers as stb reads them: segments by their length, entropy-coded data (after SOS) up to the
    // next marker (FF followed by neither 00 nor a restart marker); a DHT segment may hold several
    // tables of 1 + 16 + (number of codes) bytes each.
    StbCursor c{bytes, jpegStart(bytes)};
    if (c.pos == 0) return "";
    while (c.pos + 1 < bytes.size()) {
        if (c.peek(0) != 0xFF) {
            ++c.pos;  // entropy-coded data
            continue;
        }
        const unsigned marker = c.peek(1);
        if (marker == 0xFF) {
            ++c.pos;  // fill byte
            continue;
        }
        if (marker == 0x00 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) {
            c.pos += 2;  // stuffed byte, TEM, restart markers, SOI: no length
            continue;
        }
        if (marker == 0xD9) break;  // EOI
        const size_t length = (c.peek(2) << 8) | c.peek(3);
        if (marker == 0xC4) {
            StbCursor t{bytes, c.pos + 4};
            for (long remaining = long(length) - 2; remaining > 0;) {
                unsigned codes = 0;
                for (size_t i = 1; i <= 16; ++i) codes += t.peek(i);
                if (codes > 256)
                    return "JPEG Huffman table holds " + std::to_string(codes) + " codes, at most 256 are possible (corrupt file)";
                t.pos += 17 + codes;
                remaining -= long(17 + codes);
            }
        }
        c.pos += 2 + length;
    }
    return "";
}

std::string hdrRunLengthProblem(const std::string& bytes) {
    // stbi__hdr_load's header: identifier, lines up to an empty one, "-Y <h> +X <w>".
    StbCursor c{bytes};
    const std::string id = hdrToken(c);
    if (id != "#?RADIANCE" && id != "#?RGBE") return "";
    while (!hdrToken(c).empty()) {
    }
    const std::string size = hdrToken(c);
    if (!stbStartsWith(size, "-Y ")) return "";
    char* end = nullptr;
    const long height = std::strtol(size.c_str() + 3, &end, 10);
    while (*end == ' ') ++end;
    if (!stbStartsWith(end, "+X ")) return "";
    const long width = std::strtol(end + 3, nullptr, 10);
    if (width <= 0 || height <= 0) return "";  // stb refuses or decodes nothing
    // The walk below reads every scanline header; declaredSizeProblem has bounded their number.
    if (width < 8 || width >= 32768) return "";  // flat pixels only: stb reads them with bounded work
    for (long j = 0; j < height; ++j) {
        const unsigned c1 = c.get(), c2 = c.get(), lenHigh = c.get();
        if (c1 != 2 || c2 != 2 || (lenHigh & 0x80)) return "";  // stb reads the rest as flat pixels
        if (long((lenHigh << 8) | c.get()) != width) return "";  // stb refuses the scanline itself
        for (int k = 0; k < 4; ++k)
            for (long i = 0; i < width;) {
                unsigned count = c.get();
                if (count > 128) {
                    c.get();
                    count -= 128;
                    if (long(count) > width - i) return "";  // stb refuses: bad RLE data
                } else {
                    if (count == 0)
                        return "HDR scanline " + std::to_string(j) + " holds a run of length 0 (corrupt or truncated file)";
                    if (long(count) > width - i) return "";
                    c.pos += count;
                }
                i += long(count);
            }
    }
    return "";
}

StbFormat stbFormatOf(const std::string& bytes) {
    auto byte = [&](size_t i) { return i < bytes.size() ? static_cast<unsigned char>(bytes[i]) : 0u; };
    if (jpegStart(bytes) > 0) return StbFormat::Jpeg;
    if (byte(0) == 0x89 && byte(1) == 'P' && byte(2) == 'N' && byte(3) == 'G') return StbFormat::Png;
    if (stbStartsWith(bytes, "BM")) return StbFormat::Bmp;
    if (stbStartsWith(bytes, "#?")) return StbFormat::Hdr;
    return StbFormat::Tga;  // the one enabled format without a magic number, which stb tries last
}

std::string declaredSizeProblem(const std::string& bytes, long width, long height) {
    // The densest encoding of each format, in pixels per byte of the file: JPEG one Huffman code of
    // at least 1 bit per 8x8 block in a progressive DC scan (512); PNG deflate's 1032:1 of 1-bit
    // pixels (8256); BMP 1-bit pixels, stb reads no RLE (8); Radiance run-length scanlines 127
    // pixels per 2 bytes and channel (16); TGA run-length packets of 128 pixels in 2 bytes (64).
    static const char* const kName[] = {"JPEG", "PNG", "BMP", "HDR", "TGA"};
    static const double kPixelsPerByte[] = {512, 8256, 8, 16, 64};
    const int f = int(stbFormatOf(bytes));
    if (double(width) * double(height) <= kPixelsPerByte[f] * double(bytes.size())) return "";
    return std::string(kName[f]) + " declares " + std::to_string(width) + " x " + std::to_string(height) +
           " pixels, more than its " + std::to_string(bytes.size()) + " bytes can encode (at most " +
           std::to_string(long(kPixelsPerByte[f])) + " per byte): a truncated or corrupt file";
}

std::string pngChunkProblem(const std::string& bytes) {
    // Chunks as stb reads them: length, type, data, CRC, up to IEND.
    StbCursor c{bytes, 8};
    bool sawData = false;
    while (!c.atEnd()) {
        const uint32_t length = uint32_t(c.peek(0)) << 24 | c.peek(1) << 16 | c.peek(2) << 8 | c.peek(3);
        const std::string type{char(c.peek(4)), char(c.peek(5)), char(c.peek(6)), char(c.peek(7))};
        if (type == "IEND") break;
        if (type == "IDAT") {
            if (length == 0 && !sawData)
                return "PNG image data begins with an empty IDAT chunk, which this build's stb_image (2.27) cannot read";
            // stb grows its buffer to the chunk's declared length before it reads the chunk.
            const size_t left = bytes.size() - std::min(bytes.size(), c.pos + 8);
            if (size_t(length) > left)
                return "PNG IDAT chunk at byte " + std::to_string(c.pos) + " declares " + std::to_string(length) +
                       " bytes, but only " + std::to_string(left) + " follow (a truncated or corrupt file)";
            sawData = true;
        }
        c.pos += 12 + size_t(length);
    }
    return "";
}

std::string stbInputProblem(const std::string& bytes) {
    switch (stbFormatOf(bytes)) {
        case StbFormat::Jpeg: return jpegHuffmanProblem(bytes);
        case StbFormat::Png: return pngChunkProblem(bytes);
        case StbFormat::Hdr: return hdrRunLengthProblem(bytes);
        default: return "";
    }
}

Image decodeStbImage(const std::string& bytes, const std::string& name) {
    if (bytes.size() > size_t(INT_MAX)) stbFail(name, "file too large for the 8-bit image decoder");
    const auto* mem = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int len = int(bytes.size());
    int w = 0, h = 0, comp = 0;
    if (const std::string why = stbInputProblem(bytes); !why.empty()) stbFail(name, why);
    // stb_image allocates its output (and, for JPEG, a plane per component) from the header's size
    // before it reads the data: up to 4 bytes per channel of its output and as much again inside.
    if (stbi_info_from_memory(mem, len, &w, &h, &comp)) {
        if (const std::string why = declaredSizeProblem(bytes, w, h); !why.empty()) stbFail(name, why);
        requireDecodeMemory(w, h, 2 * 4 * std::max(comp, 3), name);
    }
    if (stbi_is_hdr_from_memory(mem, len)) {
        std::unique_ptr<float, void (*)(void*)> px(stbi_loadf_from_memory(mem, len, &w, &h, &comp, 3), stbi_image_free);
        if (!px) stbFail(name, std::string("cannot decode image: ") + stbi_failure_reason());
        requirePixels(w, h, name);
        Image img(w, h);
        std::memcpy(img.data.data(), px.get(), img.data.size() * sizeof(float));
        return img;
    }
    if (stbi_is_16_bit_from_memory(mem, len)) {
        std::unique_ptr<stbi_us, void (*)(void*)> px(stbi_load_16_from_memory(mem, len, &w, &h, &comp, 3),
                                                     stbi_image_free);
        if (!px) stbFail(name, std::string("cannot decode image: ") + stbi_failure_reason());
        requirePixels(w, h, name);
        Image img(w, h);
        for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = srgbToLinear(float(px.get()[i]) / 65535.f);
        return img;
    }
    std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load_from_memory(mem, len, &w, &h, &comp, 3), stbi_image_free);
    if (!px)
        stbFail(name, std::string("not an EXR, PFM or image format stb_image can decode (") + stbi_failure_reason() + ")");
    requirePixels(w, h, name);
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinear(float(i) / 255.f);
        return t;
    }();
    Image img(w, h);
    for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = table[px.get()[i]];
    return img;
}


}  // namespace rrf
