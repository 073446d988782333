#pragma once
/// Reading and writing images (core/util/image.h).
///
/// Formats:
///  - EXR: 32-bit float RGB, linear, ZIP-compressed (lossless). Reading accepts any channel layout
///    that has R, G and B (exact names, or one layer's "<layer>.R/.G/.B"), or a single channel
///    (greyscale, e.g. "Y"); half, float and uint channels; scanline or tiled single-part files.
///  - PFM: "PF\n<w> <h>\n-1.0\n" then little-endian floats, bottom row first (the PFM convention;
///    Image itself is top row first). Reading accepts both byte orders and colour "PF" or
///    greyscale "Pf". The magnitude of the scale field is ignored, as common tools do.
///  - PNG: tone-mapped for display: value · 2^exposure, clamped to [0, 1], exact sRGB curve, 8 bit
///    with rounding. Reading decodes 8- and 16-bit PNG, JPEG, BMP and TGA through stb_image
///    (core/util/stb_reader.h) through the sRGB curve back to linear; Radiance .hdr is read as
///    linear. GIF, PSD, PIC and PNM are not read.
///
/// All writes are atomic (core/util/atomic_file.h): a reader never sees a half-written image, and a
/// refused or failed write leaves neither the destination nor a temporary file behind.
/// Errors are std::runtime_error whose message starts with the file name.

#include <string>

#include "core/util/image.h"

namespace rrf {

enum class ImageFormat { EXR, PFM, PNG };

/// "exr", "pfm" or "png" (case-insensitive). Throws std::invalid_argument listing the accepted names.
ImageFormat imageFormatFromName(const std::string& name);

/// The format named by the extension of `path` (".exr", ".pfm", ".png", case-insensitive).
/// Throws std::invalid_argument naming the path and the accepted extensions.
ImageFormat imageFormatFromPath(const std::string& path);

/// Lower-case name of a format ("exr", "pfm", "png"); also its file extension without the dot.
const char* imageFormatName(ImageFormat format);

/// Writes `image` to `path` in `format`, atomically.
/// `exposureStops` scales values by 2^exposureStops before PNG tone mapping; EXR and PFM store the
/// radiance unchanged (they are data, not pictures) and ignore it.
/// Throws std::runtime_error naming the file if the image is empty, contains NaN/Inf pixels (the
/// message gives their count), or cannot be encoded or written; std::invalid_argument if
/// exposureStops is not finite.
void writeImage(const std::string& path, const Image& image, ImageFormat format, float exposureStops = 0.f);

/// Reads an EXR, PFM or 8/16-bit image (format from the file's magic bytes, not its name).
/// Throws std::runtime_error naming the file and what is wrong for missing, truncated or malformed
/// files. A PFM must hold the pixels its header declares; an EXR's or stb format's declared size,
/// which compressed data need not back, is checked against the memory budget
/// (core/util/memory_budget.h) before the decoder allocates for it (an InputError naming the file).
Image readImage(const std::string& path);

/// In-memory encoders behind writeImage(), for callers that store images inside other files.
/// They apply the same NaN/Inf check; `name` only labels error messages.
std::string encodeImage(const Image& image, ImageFormat format, float exposureStops = 0.f,
                        const std::string& name = "<memory>");

/// In-memory decoder behind readImage(); `name` only labels error messages.
Image decodeImage(const std::string& bytes, const std::string& name = "<memory>");

}  // namespace rrf
