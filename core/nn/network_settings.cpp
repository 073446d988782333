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
            if (used != part.size() || v < 1 || v > 4096) throw std::invalid_argument(part);
            sizes.push_back(v);
        } catch (const std::exception&) {
            throw SettingError(setting, "expected comma-separated layer sizes in 1..4096 (e.g. 20,10), got '" + text + "'");
        }
    }
    if (sizes.empty()) throw SettingError(setting, "expected at least one hidden layer size, got '" + text + "'");
    return sizes;
}

NetworkSettings NetworkSettings::fromJson(const nlohmann::json& n, const nlohmann::json* trainer, const std::string& file) {
    NetworkSettings s;
    s.options.targets = TargetMode::Separate;  // the project default (see the header), whatever nn/object_training.h defaults to
    if (!n.is_object()) throw InputError(file, "/network", "expected an object");
    for (auto it = n.begin(); it != n.end(); ++it)
        if (it.key() != "hidden" && it.key() != "activation" && it.key() != "targets")
            throw InputError(file, "/network/" + it.key(), "unknown key (known: hidden, activation, targets)");
    if (n.contains("hidden")) {
        const nlohmann::json& h = n.at("hidden");
        if (!h.is_array() || h.empty()) throw InputError(file, "/network/hidden", "expected a non-empty array of layer sizes");
        s.options.hidden.clear();
        for (size_t i = 0; i < h.size(); ++i) {
            // Range-check the 64-bit value: get<int>() would wrap 4294967316 to 20.
            if (!h[i].is_number_integer() || h[i].get<int64_t>() < 1 || h[i].get<int64_t>() > 4096)
                throw InputError(file, "/network/hidden/" + std::to_string(i), "expected a layer size in 1..4096");
            s.options.hidden.push_back(h[i].get<int>());
        }
    }
    try {
        if (n.contains("activation")) s.options.activation = parseActivation(n.at("activation").get<std::string>());
    } catch (const std::exception& e) {
        throw InputError(file, "/network/activation", std::string("expected \"tanh\" or \"relu\": ") + e.what());
    }
    try {
        if (n.contains("targets")) s.options.targets = parseTargetMode(n.at("targets").get<std::string>());
    } catch (const std::exception& e) {
        throw InputError(file, "/network/targets",
                         std::string("expected \"separate\", \"joint\", \"global\", \"direct\" or \"indirect\": ") + e.what());
    }
    if (trainer) s.options.trainer = TrainerConfig::fromJson(*trainer, file, "/trainer");
    return s;
}

nlohmann::json NetworkSettings::networkJson() const {
    return {{"hidden", options.hidden},
            {"activation", activationName(options.activation)},
            {"targets", targetModeName(options.targets)}};
}

}  // namespace rrf
