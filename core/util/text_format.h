#pragma once
/// Small text formats shared by reports, file headers, the CLI and the benchmarks.

#include <cstdint>
#include <string>

namespace rrf {

/// Shortest readable form of a number for messages ("0.1", "1e+06"), unlike std::to_string's "0.100000".
std::string formatNumber(double v);

/// "1.23 M", "456.0 k", "12 " — a count or rate with an SI prefix and a trailing space, so that a
/// unit can follow directly ("1.23 Msamples/s").
std::string humanCount(double value);

/// Lower-case hexadecimal without prefix, as scene hashes are written in dataset, model and render
/// headers (read back with std::stoull(text, nullptr, 16)).
std::string hexString(uint64_t value);

/// Exactly 16 lower-case hexadecimal digits (leading zeros kept): checksums and the keys of the
/// reference store, whose fields have a fixed width.
std::string hexString16(uint64_t value);

/// An image size as tables and legends write it: "256x256".
std::string sizeText(int width, int height);

}  // namespace rrf
