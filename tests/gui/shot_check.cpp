// rrf_gui_shotcheck shot.png [--views N]: checks that a workbench screenshot is not blank.
//
// The whole image must show many distinct colours, and the views band of the default layout
// (right of the left column, below the toolbars) must hold N (default 1) non-uniform thirds:
// 1 = the ground truth is shown, 3 = ground truth, prediction (or compared run) and error map are
// all filled.
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
}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: rrf_gui_shotcheck shot.png [--views N]\n");
        return 2;
    }
    int views = 1;
    if (argc == 4 && std::strcmp(argv[2], "--views") == 0) views = std::atoi(argv[3]);
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
    std::printf(ok ? "OK\n" : "screenshot check FAILED\n");
    return ok ? 0 : 1;
}
