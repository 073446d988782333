#pragma once
/// Small images written pixel by pixel, for the metric tests.

#include <initializer_list>

#include "core/util/image.h"

namespace rrf::test {

/// A w×h image whose pixels, in row-major order, are `pixels`.
inline Image imageOf(int w, int h, std::initializer_list<Vec3> pixels) {
    Image im(w, h);
    int i = 0;
    for (const Vec3& p : pixels) {
        im.set(i % w, i / w, p);
        ++i;
    }
    return im;
}

}  // namespace rrf::test
