// Sparse Adam of encoding parameters: per-entry bias correction against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "core/nn/trainers/sparse_adam.h"

namespace test_sparse_adam {

constexpr float kB1 = 0.9f, kB2 = 0.99f, kLr = 0.01f, kEps = 1e-8f;

/// Adds gradient g to entry i and marks it touched (twice, as a batch that reads it twice would).
void touch(rrf::SparseAdam& a, int64_t i, float g) {
    a.grad[i] += g;
    a.touched.push_back(i);
    a.touched.push_back(i);
}

}  // namespace test_sparse_adam

TEST(SparseAdam, LateFirstStepIsLearningRateTimesSignOfGradient) {
    using namespace test_sparse_adam;
    rrf::SparseAdam adam(3);
    rrf::VecX<float> e = rrf::VecX<float>::Zero(3);
    // Entry 0 takes 20 steps alone; entry 1 is touched for the first time at step 21.
    for (int s = 0; s < 20; ++s) {
        touch(adam, 0, 0.5f);
        adam.step(e, kB1, kB2, kLr, kEps);
    }
    EXPECT_EQ(e[1], 0.0f);
    const float g = 0.25f;
    touch(adam, 1, g);
    adam.step(e, kB1, kB2, kLr, kEps);
    // First Adam step: m̂ = g, v̂ = g², so the entry moves by lr·g/(|g| + ε), whatever the global step.
    EXPECT_NEAR(e[1], -double(kLr) * g / (std::abs(g) + kEps), 1e-9);
    EXPECT_EQ(e[2], 0.0f);       // never touched: unchanged
    EXPECT_EQ(adam.steps[0], 20u);
    EXPECT_EQ(adam.steps[1], 1u);  // touched twice in one batch, stepped once
    EXPECT_EQ(adam.steps[2], 0u);
    EXPECT_TRUE(adam.touched.empty());
    EXPECT_EQ(adam.grad[1], 0.0f);
}

TEST(SparseAdam, SecondVisitMatchesTwoStepAdam) {
    using namespace test_sparse_adam;
    rrf::SparseAdam adam(2);
    rrf::VecX<float> e = rrf::VecX<float>::Zero(2);
    const double g1 = -0.3, g2 = 0.7;
    touch(adam, 1, float(g1));
    adam.step(e, kB1, kB2, kLr, kEps);
    for (int s = 0; s < 5; ++s) {  // other entries' steps in between must not age entry 1
        touch(adam, 0, 1.0f);
        adam.step(e, kB1, kB2, kLr, kEps);
    }
    touch(adam, 1, float(g2));
    adam.step(e, kB1, kB2, kLr, kEps);
    // Two Adam steps written out in double: t = 1 with g1, then t = 2 with g2.
    const double b1 = kB1, b2 = kB2, lr = kLr, eps = kEps;
    double x = 0, m = (1 - b1) * g1, v = (1 - b2) * g1 * g1;
    x -= lr * (m / (1 - b1)) / (std::sqrt(v / (1 - b2)) + eps);
    m = b1 * m + (1 - b1) * g2;
    v = b2 * v + (1 - b2) * g2 * g2;
    x -= lr * (m / (1 - b1 * b1)) / (std::sqrt(v / (1 - b2 * b2)) + eps);
    EXPECT_NEAR(e[1], x, 1e-7);
    EXPECT_EQ(adam.steps[1], 2u);
}
