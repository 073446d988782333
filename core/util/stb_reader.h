#pragma once
/// Reading PNG, JPEG, BMP, TGA and Radiance HDR images through stb_image (core/util/image_io.h's
/// readImage for every file that is neither EXR nor PFM), with checks of the bytes before stb sees
/// them. Only those five formats are compiled in: Debian bookworm's stb_image 2.27 has known
/// memory-safety bugs in its GIF, PSD, PIC and PNM decoders (fixed upstream in 2.28), and no image
/// this project reads or writes comes in them. The checks stand in for the fixes of the 2.27 bugs
/// in the five that the image fuzz target (tests/fuzz/image.cpp) reaches within seconds:
///  - a JPEG Huffman table of more than 256 codes: 2.27 writes the code lengths past its 257-byte
///    array before it checks them (stb issues #1289, #1291);
///  - a Radiance HDR run-length scanline with a literal run of length 0: 2.27 loops forever on it,
///    and on the zeros it reads past the end of a truncated file (CVE-2021-42715);
///  - a PNG whose first image data chunk (IDAT) is empty: 2.27 copies 0 bytes to a null buffer,
///    undefined behaviour that the sanitizer builds abort on (valid but never written by encoders).
/// Each check walks the bytes the way stb reads them, so it refuses exactly the inputs that would
/// reach the bug, and a valid image is never refused. Beside them, a file that declares more pixels
/// than its format could encode in its bytes is refused: stb would otherwise decode zeros past the
/// end of a tiny file for millions of pixels (seconds of work per fuzz input, minutes for a forged
/// file of the memory budget's size).

#include <string>

#include "core/util/image.h"

namespace rrf {

/// Decodes `bytes` (8- and 16-bit images through the sRGB curve to linear, HDR as it is) into RGB.
/// Throws std::runtime_error whose message starts with `name` for bytes the checks below refuse,
/// that stb cannot decode or that hold no pixels, and InputError (naming `name`) when the declared
/// size exceeds the memory budget (core/util/memory_budget.h).
Image decodeStbImage(const std::string& bytes, const std::string& name);

/// The stb formats image_io enables, told apart as stb does (TGA has no magic number).
enum class StbFormat { Jpeg, Png, Bmp, Hdr, Tga };

/// The format of `bytes` (TGA for anything without a known magic number).
StbFormat stbFormatOf(const std::string& bytes);

/// "" when `bytes` reach none of the bugs above (or are not JPEG, PNG or HDR); otherwise what is
/// wrong with them, for a message that starts with the file's name.
std::string stbInputProblem(const std::string& bytes);

/// "" when `width` x `height` pixels (from the header, stbi_info) can be encoded in `bytes` at its
/// format's densest encoding; otherwise what is wrong.
std::string declaredSizeProblem(const std::string& bytes, long width, long height);

/// The JPEG check alone ("" for a valid JPEG).
std::string jpegHuffmanProblem(const std::string& bytes);

/// The HDR check alone ("" for a valid HDR file).
std::string hdrRunLengthProblem(const std::string& bytes);

/// The PNG check alone ("" unless the first IDAT chunk is empty).
std::string pngEmptyDataProblem(const std::string& bytes);

}  // namespace rrf
