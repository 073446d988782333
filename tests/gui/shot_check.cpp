// rrf_gui_shotcheck shot.png [--views N]: checks that a workbench screenshot shows the Cornell box.
//
// The whole image must show many distinct colours, and the views band of the default layout
// (right of the left column, below the toolbars) must hold N (default 1) non-uniform thirds:
// 1 = the ground truth is shown, 3 = ground truth, prediction (or compared run) and error map are
// all filled. Counting colours cannot tell a picture from noise or a mirrored image, so the images
// of the scene (the first view, and the second when N ≥ 2) must also show the Cornell box the right
// way round: a red wall left of a green wall, each covering a real part of the view (--scene-views K
// checks only the first K: a partial model's prediction may leave walls hatched). The error map
// (third view) uses a colour scale, not the scene's colours, so it must differ from the first view.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>

#include "core/util/image_io.h"

namespace {
/// Distinct 8-bit colours in [x0, x1) × [y0, y1).
size_t distinctColours(const rrf::Image& img, int x0, int y0, int x1, int y1) {
    std::set<uint32_t> colours;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const rrf::Vec3 c = img.at(x, y);
            auto q = [](float v) { return uint32_t(rrf::linearToSrgb(v < 0 ? 0 : v > 1 ? 1 : v) * 255.f + 0.5f); };
            colours.insert(q(c.x) << 16 | q(c.y) << 8 | q(c.z));
        }
    return colours.size();
}
/// Pixels of [x0, x1) × [y0, y1) whose colour is clearly red (R well above G and B) or clearly green,
/// and their mean x: the Cornell box's left and right walls.
struct WallColours {
    long red = 0, green = 0;
    double redX = 0, greenX = 0;
};
WallColours wallColours(const rrf::Image& img, int x0, int y0, int x1, int y1) {
    WallColours w;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const rrf::Vec3 c = img.at(x, y);
            if (c.x > 0.02f && c.x > 6.f * c.y && c.x > 6.f * c.z) {
                ++w.red;
                w.redX += x;
            } else if (c.y > 0.02f && c.y > 2.f * c.x && c.y > 2.f * c.z) {
                ++w.green;
                w.greenX += x;
            }
        }
    if (w.red) w.redX /= double(w.red);
    if (w.green) w.greenX /= double(w.green);
    return w;
}

/// Mean absolute difference of two equally sized regions (linear RGB, clamped to [0, 1]).
double meanDifference(const rrf::Image& img, int ax, int bx, int y0, int width, int y1) {
    double sum = 0;
    long n = 0;
    auto clamp = [](float v) { return v < 0 ? 0.f : v > 1 ? 1.f : v; };
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < width; ++x) {
            const rrf::Vec3 a = img.at(ax + x, y), b = img.at(bx + x, y);
            sum += std::fabs(clamp(a.x) - clamp(b.x)) + std::fabs(clamp(a.y) - clamp(b.y)) + std::fabs(clamp(a.z) - clamp(b.z));
            ++n;
        }
    return n ? sum / (3.0 * double(n)) : 0.0;
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: rrf_gui_shotcheck shot.png [--views N] [--scene-views K]\n");
        return 2;
    }
    int views = 1;
    int sceneViews = -1;  // leading views that must show the scene's walls; default min(N, 2)
    for (int i = 2; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--views") == 0) views = std::atoi(argv[i + 1]);
        else if (std::strcmp(argv[i], "--scene-views") == 0) sceneViews = std::atoi(argv[i + 1]);
    }
    if (sceneViews < 0) sceneViews = std::min(views, 2);
    rrf::Image img;
    try {
        img = rrf::readImage(argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "FAIL: %s\n", e.what());
        return 1;
    }
    const size_t total = distinctColours(img, 0, 0, img.width, img.height);
    std::printf("%s: %dx%d, %zu distinct colours\n", argv[1], img.width, img.height, total);
    bool ok = total >= 1000;
    if (!ok) std::printf("FAIL: fewer than 1000 distinct colours: the screenshot looks blank\n");
    // Default layout: left column 27 % of the width; the views sit in the upper part of the centre pane.
    const int x0 = int(0.28 * img.width), x1 = img.width - 8;
    const int y0 = int(0.16 * img.height), y1 = int(0.42 * img.height);
    for (int i = 0; i < 3; ++i) {
        const int a = x0 + (x1 - x0) * i / 3 + 8, b = x0 + (x1 - x0) * (i + 1) / 3 - 8;
        const size_t n = distinctColours(img, a, y0, b, y1);
        const bool filled = n >= 200;
        std::printf("view %d (x %d..%d, y %d..%d): %zu distinct colours%s\n", i, a, b, y0, y1, n,
                    filled ? "" : " (empty)");
        if (i < views && !filled) {
            std::printf("FAIL: view %d is not filled\n", i);
            ok = false;
        }
    }
    // The scene's images: red wall left of green wall, each at least 1 % of the view.
    for (int i = 0; i < std::min(sceneViews, 2); ++i) {
        const int a = x0 + (x1 - x0) * i / 3 + 8, b = x0 + (x1 - x0) * (i + 1) / 3 - 8;
        const WallColours w = wallColours(img, a, y0, b, y1);
        const long area = long(b - a) * long(y1 - y0);
        std::printf("view %d: %ld red pixels (mean x %.0f), %ld green pixels (mean x %.0f)\n", i, w.red, w.redX, w.green,
                    w.greenX);
        if (w.red * 100 < area || w.green * 100 < area || !(w.redX < w.greenX)) {
            std::printf("FAIL: view %d does not show the Cornell box's red wall left of its green wall\n", i);
            ok = false;
        }
    }
    if (views >= 3) {
        const int a0 = x0 + 8, a2 = x0 + (x1 - x0) * 2 / 3 + 8, width = (x1 - x0) / 3 - 16;
        const double d = meanDifference(img, a0, a2, y0, width, y1);
        std::printf("error map vs ground truth: mean difference %.3f\n", d);
        if (d < 0.02) {
            std::printf("FAIL: the error map shows the ground truth image\n");
            ok = false;
        }
    }
    std::printf(ok ? "OK\n" : "screenshot check FAILED\n");
    return ok ? 0 : 1;
}
