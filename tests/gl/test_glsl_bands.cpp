// A full-quality GLSL frame rendered in bands of rows (app/gui/prediction_bands.h, issue 29: the
// workbench spreads a slow frame over many UI frames) must be the frame rendered in one call: the
// first band renders the G-buffer (and the exact direct light's inputs) and later bands reuse them,
// so every band split, the band policy's included, gives the same images to float rounding.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "app/gl/glsl_predictor.h"
#include "app/gui/prediction_bands.h"
#include "tests/gl/gl_test_env.h"
#include "tests/gl/glsl_comparison.h"
#include "tests/gl/test_models.h"

namespace rrf::test_glsl_bands {
namespace {

/// Renders the frame as bands of the given heights, bottom up (GL rows), as the workbench does.
void renderInBands(GlslPredictor& gp, const std::vector<int>& heights) {
    int row = 0;
    for (int h : heights) {
        const int end = std::min(gp.camera().height, row + h);
        gp.render(row, end);
        row = end;
    }
    ASSERT_EQ(row, gp.camera().height) << "the bands cover the frame";
}

/// Band heights as the workbench's policy picks them when a row costs `secondsPerRow`.
std::vector<int> policyBands(int height, double secondsPerRow) {
    std::vector<int> bands;
    int rows = firstBandRows(height, 0.0);  // the first frame of new models: cost unknown
    for (int done = 0; done < height;) {
        rows = std::min(rows, height - done);
        bands.push_back(rows);
        done += rows;
        rows = nextBandRows(rows, rows * secondsPerRow, height);
    }
    return bands;
}

}  // namespace

TEST(GlslBands, AFrameInBandsEqualsTheWholeFrame) {
    RRF_REQUIRE_GL();
    const Scene scene = test::cornellBox();
    const ModelSet set = test::mixedModelSet(scene);
    GlslPredictor gp(scene, set);
    Camera camera = scene.camera;
    camera.width = 96;
    camera.height = 72;
    gp.setCamera(camera);
    gp.setPrediction(test::liveSettings());
    gp.setLightPosition(scene.lightRegion.lo * 0.3f + scene.lightRegion.hi * 0.7f);

    gp.render();
    Image whole[kTermCount];
    for (Term t : kTerms) whole[int(t)] = gp.read(t);
    double lit = 0.0;
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) lit += whole[int(Term::Global)].at(x, y).x;
    ASSERT_GT(lit, 0.0) << "the frame shows something to compare";

    // The policy's bands on llvmpipe's cost (one or two rows per band) and on a fast device
    // (growing bands), and an irregular split with a one-row band at the top.
    const std::vector<std::vector<int>> splits = {policyBands(camera.height, kBandBudgetSeconds),
                                                  policyBands(camera.height, kBandBudgetSeconds / 40),
                                                  {5, 1, 30, 17, 18, 1}};
    for (const std::vector<int>& bands : splits) {
        ASSERT_GT(bands.size(), 1u);
        // Clear the outputs' history first: a frame of another light, so a band that rendered
        // nothing would keep a visibly different image.
        gp.setLightPosition(scene.lightRegion.lo);
        gp.render();
        gp.setLightPosition(scene.lightRegion.lo * 0.3f + scene.lightRegion.hi * 0.7f);
        renderInBands(gp, bands);
        for (Term t : kTerms) {
            const double d = test::maxRelativeDifference(gp.read(t), whole[int(t)]);
            std::printf("  %zu bands, %s: max relative difference %.3g\n", bands.size(), termName(t), d);
            EXPECT_LE(d, 1e-5) << bands.size() << " bands, term " << termName(t);
        }
    }
}

}  // namespace rrf::test_glsl_bands
