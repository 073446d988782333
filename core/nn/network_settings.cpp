#include "core/nn/network_settings.h"

#include <sstream>

#include "core/util/error.h"

namespace rrf {

std::vector<int> parseHiddenSizes(const std::string& text, const std::string& setting) {
    std::vector<int> sizes;
    std::istringstream in(text);
    std::string part;
    while (std::getline(in, part, ',')) {
        try {
            size_t used = 0;
            const int v = std::stoi(part, &used);
            if (used != part.size() || v < 1 || v > kMaxHiddenSize) throw std::invalid_argument(part);
            sizes.push_back(v);
        } catch (const std::exception&) {
            throw SettingError(setting, "expected comma-separated layer sizes in 1.." + std::to_string(kMaxHiddenSize) +
                                            " (e.g. 20,10), got '" + text + "'");
        }
    }
    if (sizes.empty()) throw SettingError(setting, "expected at least one hidden layer size, got '" + text + "'");
    return sizes;
}

std::string hiddenSizesText(const std::vector<int>& sizes) {
    std::string t;
    for (size_t i = 0; i < sizes.size(); ++i) t += (i ? "," : "") + std::to_string(sizes[i]);
    return t;
}

const std::vector<std::string>& NetworkSettings::keys() {
    static const std::vector<std::string> k = {"hidden",  "activation", "ensemble", "inputs",
                                               "encoding", "objects",   "targets",  "partition"};
    return k;
}

}  // namespace rrf
