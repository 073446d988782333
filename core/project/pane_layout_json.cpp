// The project's "layout" section in JSON (see pane_layout_json.h).
#include "core/project/pane_layout_json.h"

#include <cstdio>

namespace rrf {

using nlohmann::json;

namespace {

/// A fraction for messages: "%g" prints the float as written ("0.92"), not its double expansion.
std::string fractionText(float f) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", double(f));
    return buf;
}

const char* splitName(PaneSplit s) { return s == PaneSplit::Row ? "row" : "column"; }

json nodeJson(const PaneNode& n) {
    if (n.isLeaf()) return json{{"tabs", n.tabs}, {"active", n.active}};
    return json{{"split", splitName(n.split)},
                {"fraction", n.fraction},
                {"panes", json::array({nodeJson(n.children[0]), nodeJson(n.children[1])})}};
}

/// Reads one node; a structural fault throws (the caller falls back to the default tree), a bad
/// fraction is clamped with a warning.
PaneNode readNode(const JsonReader& r, int depth, std::vector<std::string>& warnings) {
    if (depth > PaneLayout::kMaxDepth)
        r.fail("panes nested deeper than " + std::to_string(PaneLayout::kMaxDepth) + " levels");
    r.requireObject();
    PaneNode n;
    if (!r.has("split")) {
        r.checkKeys({"tabs", "active"});
        const JsonReader tabs = r.at("tabs");
        for (size_t i = 0, count = tabs.requireArray(); i < count; ++i) n.tabs.push_back(tabs.at(i).string());
        n.active = r.stringOr("active", "");
        return n;
    }
    r.checkKeys({"split", "fraction", "panes"});
    n.split = r.choiceOr("split", "", {"row", "column"}) == "row" ? PaneSplit::Row : PaneSplit::Column;
    const JsonReader panes = r.at("panes");
    if (panes.requireArray() != 2) panes.fail("expected an array of 2 panes, got " + JsonReader::describe(panes.value()));
    n.fraction = 0.5f;
    try {
        n.fraction = r.floatOr("fraction", 0.5f);
    } catch (const InputError& e) {
        warnings.push_back(std::string(e.what()) + "; 0.5 is used");
    }
    const float clamped = PaneLayout::clampFraction(n.fraction, 0.5f);
    if (clamped != n.fraction)
        warnings.push_back(InputError(r.file(), JsonReader::child(r.pointer(), "fraction"),
                                      "expected a number in [" + fractionText(PaneLayout::kMinFraction) + ", " +
                                          fractionText(PaneLayout::kMaxFraction) + "]; " + fractionText(clamped) +
                                          " is used")
                               .what());
    n.fraction = clamped;
    n.children.push_back(readNode(panes.at(size_t(0)), depth + 1, warnings));
    n.children.push_back(readNode(panes.at(size_t(1)), depth + 1, warnings));
    return n;
}

/// The "floating" windows; a damaged entry is dropped with a warning (its panel returns to a pane).
std::vector<FloatingPanel> readFloating(const JsonReader& section, std::vector<std::string>& warnings) {
    std::vector<FloatingPanel> out;
    if (!section.has("floating")) return out;
    const JsonReader list = section.at("floating");
    size_t count = 0;
    try {
        count = list.requireArray();
    } catch (const InputError& e) {
        warnings.push_back(std::string(e.what()) + "; no panel floats");
        return out;
    }
    for (size_t i = 0; i < count; ++i) {
        const JsonReader r = list.at(i);
        try {
            r.requireObject();
            r.checkKeys({"tab", "rect", "home"});
            FloatingPanel f;
            f.tab = r.at("tab").string();
            f.home = r.stringOr("home", "");
            const JsonReader rect = r.at("rect");
            if (rect.requireArray() != 4) rect.fail("expected [x, y, width, height]");
            float v[4];
            for (size_t k = 0; k < 4; ++k) v[k] = float(rect.at(k).number(-1e5, 1e5));
            if (v[2] < 1.f || v[3] < 1.f) rect.fail("expected a positive width and height");
            f.x = v[0], f.y = v[1], f.width = v[2], f.height = v[3];
            out.push_back(std::move(f));
        } catch (const InputError& e) {
            warnings.push_back(std::string(e.what()) + "; that panel is docked");
        }
    }
    return out;
}

}  // namespace

json toJson(const PaneLayout& layout) {
    json j{{"root", nodeJson(layout.root)}};
    if (!layout.floating.empty()) {
        json fl = json::array();
        for (const FloatingPanel& f : layout.floating)
            fl.push_back({{"tab", f.tab}, {"rect", {f.x, f.y, f.width, f.height}}, {"home", f.home}});
        j["floating"] = fl;
    }
    return j;
}

PaneLayout paneLayoutFromJson(const JsonReader& section, std::vector<std::string>& warnings) {
    PaneLayout l;
    if (!section.isObject()) {
        warnings.push_back(InputError(section.file(), section.pointer(),
                                      "expected an object, got " + JsonReader::describe(section.value()) +
                                          "; the default layout is used")
                               .what());
        return l;
    }
    if (!section.has("root")) {
        // The fixed three-pane arrangement of earlier versions: its two splitters' fractions.
        auto read = [&](const char* key, float fallback) {
            try {
                return PaneLayout::clampFraction(section.floatOr(key, fallback), fallback);
            } catch (const InputError& e) {
                warnings.push_back(std::string(e.what()) + "; the default is used");
                return fallback;
            }
        };
        l.root = PaneLayout::defaultRoot(read("left", PaneLayout::kDefaultLeft), read("bottom", PaneLayout::kDefaultBottom));
        return l;
    }
    const JsonReader root = section.at("root");
    try {
        std::vector<std::string> nodeWarnings;
        PaneNode tree = readNode(root, 0, nodeWarnings);
        std::vector<FloatingPanel> floating = readFloating(section, nodeWarnings);
        PaneLayout::normalise(tree, floating, root.file(), root.pointer(), nodeWarnings);
        l.root = std::move(tree);
        l.floating = std::move(floating);
        warnings.insert(warnings.end(), nodeWarnings.begin(), nodeWarnings.end());
    } catch (const InputError& e) {
        warnings.push_back(std::string(e.what()) + "; the default layout is used");
        l.root = PaneLayout::defaultRoot();
    }
    return l;
}

}  // namespace rrf
