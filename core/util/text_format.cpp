#include "core/util/text_format.h"

#include <cstdio>
#include <iomanip>
#include <sstream>

namespace rrf {

std::string formatNumber(double v) {
    std::ostringstream out;
    out << std::setprecision(7) << v;
    return out.str();
}

std::string humanCount(double value) {
    char buf[32];
    if (value >= 1e9) std::snprintf(buf, sizeof buf, "%.2f G", value / 1e9);
    else if (value >= 1e6) std::snprintf(buf, sizeof buf, "%.2f M", value / 1e6);
    else if (value >= 1e3) std::snprintf(buf, sizeof buf, "%.1f k", value / 1e3);
    else std::snprintf(buf, sizeof buf, "%.0f ", value);
    return buf;
}

std::string hexString(uint64_t value) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%llx", (unsigned long long)value);
    return buf;
}

std::string hexString16(uint64_t value) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)value);
    return buf;
}

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

}  // namespace rrf
