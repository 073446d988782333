#include "core/util/image_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include <tinyexr.h>

// stb_image_write is compiled into this file only, with internal linkage, so another translation
// unit (the GUI, say) can carry its own copy of stb without duplicate symbols; stb_image, the
// reader, is core/util/stb_reader.cpp's.
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include "core/util/atomic_file.h"
#include "core/util/memory_budget.h"
#include "core/util/stb_reader.h"

namespace rrf {

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
    throw std::runtime_error(name + ": " + what);
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string extensionOf(const std::string& path) {
    const size_t slash = path.find_last_of("/\\");
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    return lower(path.substr(dot + 1));
}

/// Refuses images that cannot be written meaningfully: NaN/Inf would silently become garbage in a
/// PNG and poison every later comparison in an EXR/PFM.
void checkWritable(const Image& img, const std::string& name) {
    if (img.width <= 0 || img.height <= 0)
        fail(name, "refusing to write an empty image (" + std::to_string(img.width) + "x" +
                       std::to_string(img.height) + ")");
    if (img.data.size() != 3 * img.pixelCount())
        fail(name, "image data holds " + std::to_string(img.data.size()) + " floats, expected " +
                       std::to_string(3 * img.pixelCount()) + " for " + std::to_string(img.width) + "x" +
                       std::to_string(img.height) + " RGB");
    const size_t bad = img.nonFiniteCount();
    if (bad)
        fail(name, "refusing to write an image with " + std::to_string(bad) + " NaN/Inf pixel" +
                       (bad == 1 ? "" : "s") + " of " + std::to_string(img.pixelCount()));
}

// ---- EXR ----------------------------------------------------------------------------------------

std::string takeExrError(const char* err) {
    std::string s = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    return s;
}

std::string encodeExr(const Image& img, const std::string& name) {
    // OpenEXR readers expect channels in alphabetical order, hence B, G, R.
    const size_t n = img.pixelCount();
    std::vector<float> planes[3];
    for (auto& p : planes) p.resize(n);
    for (size_t i = 0; i < n; ++i) {
        planes[0][i] = img.data[3 * i + 2];
        planes[1][i] = img.data[3 * i + 1];
        planes[2][i] = img.data[3 * i + 0];
    }
    float* ptrs[3] = {planes[0].data(), planes[1].data(), planes[2].data()};

    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = 3;
    image.images = reinterpret_cast<unsigned char**>(ptrs);
    image.width = img.width;
    image.height = img.height;

    EXRHeader header;
    InitEXRHeader(&header);
    std::array<EXRChannelInfo, 3> channels{};
    const char* names[3] = {"B", "G", "R"};
    for (int c = 0; c < 3; ++c) std::strncpy(channels[c].name, names[c], sizeof(channels[c].name) - 1);
    int types[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
    int requested[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
    header.num_channels = 3;
    header.channels = channels.data();
    header.pixel_types = types;
    header.requested_pixel_types = requested;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

    unsigned char* memory = nullptr;
    const char* err = nullptr;
    const size_t bytes = SaveEXRImageToMemory(&image, &header, &memory, &err);
    if (bytes == 0 || !memory) {
        std::free(memory);
        fail(name, "EXR encoding failed: " + takeExrError(err));
    }
    std::string out(reinterpret_cast<const char*>(memory), bytes);
    std::free(memory);
    return out;
}

/// Index of the channel called `want`, or of the only channel ending in "." + want.
int findExrChannel(const EXRHeader& h, const char* want) {
    for (int c = 0; c < h.num_channels; ++c)
        if (std::strcmp(h.channels[c].name, want) == 0) return c;
    const std::string suffix = std::string(".") + want;
    int found = -1;
    for (int c = 0; c < h.num_channels; ++c) {
        const std::string nm = h.channels[c].name;
        if (nm.size() > suffix.size() && nm.compare(nm.size() - suffix.size(), suffix.size(), suffix) == 0) {
            if (found >= 0) return -2;  // ambiguous: several layers
            found = c;
        }
    }
    return found;
}

float exrSample(const unsigned char* plane, int type, size_t i) {
    if (type == TINYEXR_PIXELTYPE_UINT) return float(reinterpret_cast<const uint32_t*>(plane)[i]);
    return reinterpret_cast<const float*>(plane)[i];  // half was requested as float
}

Image decodeExr(const std::string& bytes, const std::string& name) {
    const auto* mem = reinterpret_cast<const unsigned char*>(bytes.data());
    EXRVersion version;
    if (ParseEXRVersionFromMemory(&version, mem, bytes.size()) != TINYEXR_SUCCESS)
        fail(name, "invalid OpenEXR version header");
    if (version.multipart || version.non_image)
        fail(name, "multi-part and deep OpenEXR files are not supported");

    EXRHeader header;
    InitEXRHeader(&header);
    // Guards go first: tinyexr may leave partial allocations behind when it fails.
    std::unique_ptr<EXRHeader, int (*)(EXRHeader*)> headerGuard(&header, FreeEXRHeader);
    const char* err = nullptr;
    if (ParseEXRHeaderFromMemory(&header, &version, mem, bytes.size(), &err) != TINYEXR_SUCCESS)
        fail(name, "invalid OpenEXR header: " + takeExrError(err));

    // tinyexr allocates every channel's plane for the header's data window before it reads a pixel
    // (up to 256 GB by its own limit), so a header of a few bytes could ask for all of memory.
    const int64_t exrWidth = int64_t(header.data_window.max_x) - header.data_window.min_x + 1,
                  exrHeight = int64_t(header.data_window.max_y) - header.data_window.min_y + 1;
    if (exrWidth <= 0 || exrHeight <= 0)
        fail(name, "OpenEXR data window is empty (" + std::to_string(exrWidth) + "x" + std::to_string(exrHeight) + ")");
    requireDecodeMemory(exrWidth, exrHeight, 4 * int64_t(std::max(header.num_channels, 0)), name);

    int chan[3] = {findExrChannel(header, "R"), findExrChannel(header, "G"), findExrChannel(header, "B")};
    if (chan[0] < 0 || chan[1] < 0 || chan[2] < 0) {
        if (header.num_channels == 1) {
            chan[0] = chan[1] = chan[2] = 0;  // greyscale (Y, L, ...)
        } else {
            std::string list;
            for (int c = 0; c < header.num_channels; ++c) list += std::string(list.empty() ? "" : ", ") + header.channels[c].name;
            fail(name, "OpenEXR file has no unambiguous R, G, B channels (channels: " + list + ")");
        }
    }
    for (int c = 0; c < header.num_channels; ++c)
        if (header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF) header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;

    EXRImage image;
    InitEXRImage(&image);
    // On failure tinyexr frees the image itself (leaving the pointers dangling), so the guard is
    // armed only after success. Its cleanup loops over image.num_channels, which it sets only on
    // success; presetting it lets that cleanup free the channel planes of a corrupt file too.
    image.num_channels = header.num_channels;
    if (LoadEXRImageFromMemory(&image, &header, mem, bytes.size(), &err) != TINYEXR_SUCCESS)
        fail(name, "cannot decode OpenEXR pixel data (truncated or corrupt?): " + takeExrError(err));
    std::unique_ptr<EXRImage, int (*)(EXRImage*)> imageGuard(&image, FreeEXRImage);

    Image out(image.width, image.height);
    const int* types = header.requested_pixel_types;
    if (header.tiled) {
        // Level 0 only: mip/rip levels below it are derived data.
        const int tw = header.tile_size_x, th = header.tile_size_y;
        for (int t = 0; t < image.num_tiles; ++t) {
            const EXRTile& tile = image.tiles[t];
            for (int j = 0; j < tile.height; ++j)
                for (int i = 0; i < tile.width; ++i) {
                    const int x = tile.offset_x * tw + i, y = tile.offset_y * th + j;
                    if (x >= out.width || y >= out.height) continue;
                    const size_t k = size_t(j) * size_t(tw) + size_t(i);
                    out.set(x, y, {exrSample(tile.images[chan[0]], types[chan[0]], k),
                                   exrSample(tile.images[chan[1]], types[chan[1]], k),
                                   exrSample(tile.images[chan[2]], types[chan[2]], k)});
                }
        }
    } else {
        const size_t n = out.pixelCount();
        for (int c = 0; c < 3; ++c)
            for (size_t i = 0; i < n; ++i) out.data[3 * i + c] = exrSample(image.images[chan[c]], types[chan[c]], i);
    }
    return out;
}

// ---- PFM ----------------------------------------------------------------------------------------

std::string encodePfm(const Image& img) {
    std::string out = "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1.0\n";
    const size_t header = out.size();
    out.resize(header + 12 * img.pixelCount());
    char* dst = &out[header];
    for (int y = img.height - 1; y >= 0; --y) {  // PFM stores the bottom row first
        for (size_t i = 0; i < size_t(3 * img.width); ++i) {
            uint32_t bits;
            std::memcpy(&bits, &img.data[3 * size_t(y) * size_t(img.width) + i], 4);
            for (int b = 0; b < 4; ++b) *dst++ = char((bits >> (8 * b)) & 0xff);  // little-endian
        }
    }
    return out;
}

/// Minimal cursor over the PFM text header: every read is bounds-checked.
struct PfmCursor {
    const std::string& s;
    const std::string& name;
    size_t pos = 0;

    void skipSpace() {
        while (pos < s.size() && std::isspace(static_cast<unsigned char>(s[pos]))) ++pos;
    }
    std::string token(const char* what) {
        skipSpace();
        const size_t start = pos;
        while (pos < s.size() && pos - start < 64 && !std::isspace(static_cast<unsigned char>(s[pos]))) ++pos;
        if (pos == start) fail(name, std::string("PFM header ends before the ") + what);
        if (pos == s.size()) fail(name, std::string("PFM header ends inside the ") + what);
        return s.substr(start, pos - start);
    }
    long long integer(const char* what) {
        const std::string t = token(what);
        char* end = nullptr;
        const long long v = std::strtoll(t.c_str(), &end, 10);
        if (*end != '\0' || t[0] == '+' || t[0] == '-')
            fail(name, std::string("PFM ") + what + " '" + t + "' is not a positive integer");
        return v;
    }
};

Image decodePfm(const std::string& bytes, const std::string& name) {
    const bool color = bytes[1] == 'F';
    PfmCursor cur{bytes, name, 2};
    const long long w = cur.integer("width");
    const long long h = cur.integer("height");
    const std::string scaleText = cur.token("scale");
    char* end = nullptr;
    const double scale = std::strtod(scaleText.c_str(), &end);
    if (*end != '\0' || !std::isfinite(scale) || scale == 0)
        fail(name, "PFM scale '" + scaleText + "' is not a non-zero number");
    // Exactly one whitespace byte separates the header from the raster.
    const size_t start = cur.pos + 1;
    if (w <= 0 || h <= 0 || w > INT_MAX || h > INT_MAX)
        fail(name, "PFM size " + std::to_string(w) + "x" + std::to_string(h) + " is invalid");
    const int channels = color ? 3 : 1;
    const uint64_t available = bytes.size() - std::min<uint64_t>(bytes.size(), start);
    // Checked before allocating: w*h*12 fits in 64 bits because w, h < 2^31.
    const uint64_t needed = uint64_t(w) * uint64_t(h) * uint64_t(channels) * 4u;
    if (available < needed)
        fail(name, "PFM is truncated: " + std::to_string(w) + "x" + std::to_string(h) + (color ? " RGB" : " grey") +
                       " needs " + std::to_string(needed) + " bytes of pixel data, file has " +
                       std::to_string(available));
    const bool little = scale < 0;

    Image img(static_cast<int>(w), static_cast<int>(h));
    const unsigned char* src = reinterpret_cast<const unsigned char*>(bytes.data()) + start;
    for (int y = int(h) - 1; y >= 0; --y) {
        for (int x = 0; x < int(w); ++x) {
            float v[3];
            for (int c = 0; c < channels; ++c, src += 4) {
                const uint32_t bits = little ? uint32_t(src[0]) | uint32_t(src[1]) << 8 | uint32_t(src[2]) << 16 |
                                                   uint32_t(src[3]) << 24
                                             : uint32_t(src[3]) | uint32_t(src[2]) << 8 | uint32_t(src[1]) << 16 |
                                                   uint32_t(src[0]) << 24;
                std::memcpy(&v[c], &bits, 4);
            }
            if (!color) v[1] = v[2] = v[0];
            img.set(x, y, {v[0], v[1], v[2]});
        }
    }
    return img;
}

// ---- PNG and other 8/16-bit formats (stb) -------------------------------------------------------

std::string encodePng(const Image& img, float exposureStops, const std::string& name) {
    const double scale = std::exp2(double(exposureStops));
    std::vector<unsigned char> rgb(img.data.size());
    for (size_t i = 0; i < img.data.size(); ++i) {
        double v = double(img.data[i]) * scale;
        if (!(v > 0)) v = 0;  // also maps 0·inf = NaN from extreme exposures to black
        if (v > 1) v = 1;
        rgb[i] = static_cast<unsigned char>(std::floor(double(linearToSrgb(float(v))) * 255.0 + 0.5));
    }
    std::string out;
    auto sink = [](void* ctx, void* data, int size) {
        static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(sink, &out, img.width, img.height, 3, rgb.data(), 3 * img.width))
        fail(name, "PNG encoding failed");
    return out;
}

}  // namespace

ImageFormat imageFormatFromName(const std::string& name) {
    const std::string n = lower(name);
    if (n == "exr") return ImageFormat::EXR;
    if (n == "pfm") return ImageFormat::PFM;
    if (n == "png") return ImageFormat::PNG;
    throw std::invalid_argument("unknown image format '" + name + "' (accepted: exr, pfm, png)");
}

ImageFormat imageFormatFromPath(const std::string& path) {
    const std::string ext = extensionOf(path);
    if (ext == "exr" || ext == "pfm" || ext == "png") return imageFormatFromName(ext);
    throw std::invalid_argument(path + ": cannot tell the image format from the extension" +
                                (ext.empty() ? std::string() : " '." + ext + "'") +
                                " (accepted: .exr, .pfm, .png)");
}

const char* imageFormatName(ImageFormat format) {
    switch (format) {
        case ImageFormat::EXR: return "exr";
        case ImageFormat::PFM: return "pfm";
        case ImageFormat::PNG: return "png";
    }
    return "unknown";
}

std::string encodeImage(const Image& image, ImageFormat format, float exposureStops, const std::string& name) {
    if (!std::isfinite(exposureStops))
        throw std::invalid_argument(name + ": exposure must be finite, got " + std::to_string(exposureStops));
    checkWritable(image, name);
    switch (format) {
        case ImageFormat::EXR: return encodeExr(image, name);
        case ImageFormat::PFM: return encodePfm(image);
        case ImageFormat::PNG: return encodePng(image, exposureStops, name);
    }
    fail(name, "unknown image format");
}

void writeImage(const std::string& path, const Image& image, ImageFormat format, float exposureStops) {
    // Encode fully in memory first: a refused or failed encode never creates a file.
    writeFileAtomically(path, encodeImage(image, format, exposureStops, path));
}

Image decodeImage(const std::string& bytes, const std::string& name) {
    if (bytes.empty()) fail(name, "file is empty");
    const std::string ext = extensionOf(name);
    const bool exrMagic = bytes.size() >= 4 && static_cast<unsigned char>(bytes[0]) == 0x76 &&
                          static_cast<unsigned char>(bytes[1]) == 0x2f && static_cast<unsigned char>(bytes[2]) == 0x31 &&
                          static_cast<unsigned char>(bytes[3]) == 0x01;
    const bool pfmMagic = bytes.size() >= 3 && bytes[0] == 'P' && (bytes[1] == 'F' || bytes[1] == 'f') &&
                          std::isspace(static_cast<unsigned char>(bytes[2]));
    if (exrMagic) return decodeExr(bytes, name);
    if (pfmMagic) return decodePfm(bytes, name);
    // The name says what the user expected; say what was wrong in those terms.
    if (ext == "exr") fail(name, "not an OpenEXR file (bad magic number)");
    if (ext == "pfm") {
        std::string head;
        for (size_t i = 0; i < std::min<size_t>(2, bytes.size()); ++i)
            head += std::isprint(static_cast<unsigned char>(bytes[i])) ? bytes[i] : '?';
        fail(name, "not a PFM file: magic '" + head + "', expected 'PF' (colour) or 'Pf' (greyscale)");
    }
    return decodeStbImage(bytes, name);
}

Image readImage(const std::string& path) { return decodeImage(readFile(path), path); }

}  // namespace rrf
