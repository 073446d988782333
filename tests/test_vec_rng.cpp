#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/util/rng.h"
#include "core/util/vec3.h"

namespace test_vec_rng {

using namespace rrf;

TEST(Rng, SameKeyGivesSameSequence) {
    Rng a(7, 123, 4), b(7, 123, 4);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(a.nextU64(), b.nextU64());
}

TEST(Rng, DifferentKeysDiffer) {
    Rng a(7, 123, 4), b(7, 124, 4), c(8, 123, 4), d(7, 123, 5);
    const uint64_t va = a.nextU64();
    EXPECT_NE(va, b.nextU64());
    EXPECT_NE(va, c.nextU64());
    EXPECT_NE(va, d.nextU64());
}

TEST(Rng, UniformIsInUnitIntervalAndUnbiased) {
    // Mean of U(0,1) is 1/2 with standard deviation 1/sqrt(12 N); 6 sigma bound.
    const int n = 200000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        Rng r(1, uint64_t(i));
        const float u = r.uniform();
        ASSERT_GE(u, 0.f);
        ASSERT_LT(u, 1.f);
        sum += u;
    }
    EXPECT_NEAR(sum / n, 0.5, 6.0 / std::sqrt(12.0 * n));
}

TEST(Frame, IsOrthonormal) {
    Rng r(3, 0);
    for (int i = 0; i < 1000; ++i) {
        Vec3 n = normalize(Vec3(r.uniform() * 2 - 1, r.uniform() * 2 - 1, r.uniform() * 2 - 1));
        if (i == 0) n = Vec3(0, 0, -1);  // the branch Duff et al. fixed
        Frame f(n);
        EXPECT_NEAR(dot(f.s, f.t), 0, 1e-5);
        EXPECT_NEAR(dot(f.s, f.n), 0, 1e-5);
        EXPECT_NEAR(length(f.s), 1, 1e-5);
        EXPECT_NEAR(length(f.t), 1, 1e-5);
        Vec3 v(0.3f, -0.2f, 0.9f);
        Vec3 w = f.toLocal(f.toWorld(v));
        EXPECT_NEAR(length(w - v), 0, 1e-5);
    }
}

}  // namespace test_vec_rng
