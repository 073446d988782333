// The workbench's error figures are `rrf evaluate`'s: the Views figures (panels/view_model.h) and the
// Objects table (evaluationInfo) equal evaluate()'s for the same prediction and reference, with the
// reference's noise floor and the corrected figure, over the same footprint mask (left-out pixels
// hatched in the error map); the Objects CSV carries the noise columns, empty when unknown; the Cost
// panel draws a path tracer and a model series with the break-even sentence, in colours that follow
// the series' names.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/eval/evaluation.h"
#include "core/scene/scene_json.h"
#include "panels/panels.h"
#include "panels/plot.h"
#include "panels/view_model.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test::test_honest_figures {

using namespace rrf::panels;

namespace {

constexpr int kSize = 24;

Scene cornellBox() { return loadScene(RRF_SOURCE_DIR "/projects/cornell-box/scene.json"); }

/// A small noisy reference with its variances, and an evaluation of the exact direct light against
/// it (no networks needed: the direct term is computed with shadow rays).
struct Fixture {
    Scene scene = cornellBox();
    ModelSet models;
    PredictionSettings settings;
    Reference reference;
    Evaluation evaluation;
    std::shared_ptr<const FootprintMask> mask;
    Fixture() {
        settings.direct = PredictionSettings::Direct::Exact;
        settings.directSamples = 4;
        RenderOptions o;
        o.width = o.height = kSize;
        o.spp = 8;
        reference = renderReference(scene, scene.lightPosition(), o);
        const Predictor predictor(scene, models, settings);
        evaluation = evaluate(predictor, reference);
        // The mask as the workbench's render worker makes it: the G-buffer at the reference's light.
        mask = std::make_shared<const FootprintMask>(footprintMask(predictor.gbuffer(reference.lightPosition, kSize, kSize)));
    }
    /// The workbench state showing this reference as the ground truth and the prediction beside it.
    void fill(WorkbenchState& s) const {
        for (Term t : kTerms) {
            s.groundTruth.term(t) = reference.image(t);
            s.groundTruth.variances[int(t)] = reference.variance(t);
            s.prediction.term(t) = evaluation.prediction.image(t);
        }
        s.groundTruth.footprint = mask;
        s.groundTruth.touch();
        s.prediction.touch();
        s.view.compareSource = CompareSource::Prediction;
        s.view.term = Term::Direct;
    }
};

void expectSameStats(const ErrorStats& a, const ErrorStats& b) {
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.nonFinite, b.nonFinite);
    EXPECT_DOUBLE_EQ(a.rmse, b.rmse);
    EXPECT_DOUBLE_EQ(a.relativeRmse, b.relativeRmse);
    EXPECT_DOUBLE_EQ(a.mae, b.mae);
    EXPECT_DOUBLE_EQ(a.maxError, b.maxError);
    EXPECT_EQ(a.noiseKnown, b.noiseKnown);
    EXPECT_DOUBLE_EQ(a.rmseNoiseFloor, b.rmseNoiseFloor);
    EXPECT_DOUBLE_EQ(a.rmseCorrected, b.rmseCorrected);
    EXPECT_DOUBLE_EQ(a.relativeRmseNoiseFloor, b.relativeRmseNoiseFloor);
    EXPECT_DOUBLE_EQ(a.relativeRmseCorrected, b.relativeRmseCorrected);
}

/// A path tracer with error = 0.8/√spp at 10 ms per spp, and two models.
std::vector<CostSeries> twoSeries() {
    CostSeries pt;
    pt.name = "path tracer (sweep hidden)";
    pt.kind = CostKind::PathTracer;
    pt.noiseFloor = 0.02;
    for (int spp = 1; spp <= 256; spp *= 4) {
        CostPoint p{0.01 * spp, 0.8 / std::sqrt(double(spp)), std::to_string(spp)};
        p.spp = spp;
        pt.points.push_back(p);
    }
    CostSeries models;
    models.name = "sweep hidden";
    models.kind = CostKind::Models;
    models.pathTracer = pt.name;
    models.noiseFloor = 0.02;
    CostPoint a{20.0, 0.1, "20,10"};
    a.frameSeconds = 2.5e-3;
    a.glslFrameSeconds = 4e-4;
    CostPoint b{8.0, 0.2, "5"};
    b.frameSeconds = 1e-3;
    models.points = {a, b};
    return {pt, models};
}

bool drawListsHoldColour(ImU32 colour) {
    const ImDrawData* d = ImGui::GetDrawData();
    for (int l = 0; d && l < d->CmdListsCount; ++l)
        for (const ImDrawVert& v : d->CmdLists[l]->VtxBuffer)
            if (v.col == colour) return true;
    return false;
}

}  // namespace

using CostPanelTest = ImGuiFixture;

TEST(HonestFigures, ViewsFiguresAreThoseOfEvaluate) {
    const Fixture f;
    ASSERT_FALSE(f.reference.variance(Term::Direct).empty());
    WorkbenchState s;
    f.fill(s);
    ViewModel vm;
    vm.update(s);
    const ViewErrorStats& v = s.view.errorStats;
    ASSERT_TRUE(v.valid);
    expectSameStats(v.stats, f.evaluation.term(Term::Direct).overall);
    EXPECT_TRUE(v.stats.noiseKnown) << "the ground truth's variance makes the floor known";
    EXPECT_EQ(v.left.total(), f.evaluation.footprint.counts.total());
    ASSERT_GT(v.left.total(), 0u) << "the box has edges the mask leaves out";

    // Every pixel the mask leaves out is drawn as such in the error map, every kept one in false colour.
    const DisplayImage& map = vm.image(ViewModel::kError);
    ASSERT_EQ(map.width, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const size_t i = size_t(y) * kSize + size_t(x);
            uint8_t expected[4];
            leftOutColour(f.mask->pixel[i], x, y, expected);
            const bool hatched = std::equal(expected, expected + 4, &map.rgba[4 * i]);
            // Viridis never gives a grey, so a kept pixel cannot look left out.
            EXPECT_EQ(hatched, !f.mask->isKept(i)) << x << "," << y << " " << footprintName(f.mask->pixel[i]);
        }

    // Without the variance (e.g. a re-opened run) the floor is unknown, never 0.
    for (Term t : kTerms) s.groundTruth.variances[int(t)] = Image();
    s.groundTruth.touch();
    vm.update(s);
    EXPECT_FALSE(s.view.errorStats.stats.noiseKnown);
    EXPECT_TRUE(std::isnan(s.view.errorStats.stats.relativeRmseNoiseFloor));
    EXPECT_EQ(noiseFigureText(s.view.errorStats.stats.relativeRmseNoiseFloor), "unknown");
}

// Issue 29: while the light moves (or the scene or size changes), the ground truth shown is of the old
// one: no figure and no error map against it; the view says what it waits for; the same light again
// (the new ground truth) gives the figures back. Unstamped images (a run's) compare as before.
TEST(HonestFigures, NoErrorAgainstTheGroundTruthOfAnotherLight) {
    const Fixture f;
    WorkbenchState s;
    f.fill(s);
    const ImageStamp at{f.reference.lightPosition, f.scene.contentHash(), kSize, kSize};
    s.groundTruth.stamp = at;
    s.prediction.stamp = at;
    s.groundTruth.touch();
    s.prediction.touch();
    ViewModel vm;
    vm.update(s);
    ASSERT_TRUE(s.view.errorStats.valid);
    EXPECT_TRUE(s.view.errorStats.waiting.empty());
    EXPECT_FALSE(vm.image(ViewModel::kError).rgba.empty());

    ImageStamp moved = at;
    moved.light = at.light + Vec3(0.1f, 0.f, 0.f);
    s.prediction.stamp = moved;  // the prediction follows the dragged light at once
    s.prediction.touch();
    vm.update(s);
    EXPECT_FALSE(s.view.errorStats.valid);
    EXPECT_NE(s.view.errorStats.waiting.find("waiting for the ground truth of the light"), std::string::npos)
        << s.view.errorStats.waiting;
    EXPECT_TRUE(vm.image(ViewModel::kError).rgba.empty()) << "no error map against the old light's image";

    ImageStamp edited = at;
    edited.sceneHash ^= 1;
    s.prediction.stamp = edited;
    s.prediction.touch();
    vm.update(s);
    EXPECT_NE(s.view.errorStats.waiting.find("edited scene"), std::string::npos);

    s.groundTruth.stamp = moved;  // the render of the new light arrives
    s.prediction.stamp = moved;
    s.groundTruth.touch();
    s.prediction.touch();
    vm.update(s);
    EXPECT_TRUE(s.view.errorStats.valid);
    EXPECT_FALSE(vm.image(ViewModel::kError).rgba.empty());

    s.groundTruth.stamp.reset();  // a re-opened run's images: origin unknown
    s.groundTruth.touch();
    vm.update(s);
    EXPECT_TRUE(s.view.errorStats.valid);
}

TEST(HonestFigures, ObjectsTableIsEvaluatesWithNoiseColumns) {
    const Fixture f;
    const EvaluationInfo info = evaluationInfo(f.evaluation, f.scene, f.models);
    EXPECT_TRUE(info.referenceNoiseKnown);
    EXPECT_EQ(info.referenceSpp, 8);
    const int t = int(Term::Direct);
    expectSameStats(info.overall[t], f.evaluation.term(Term::Direct).overall);
    ASSERT_FALSE(info.rows[t].empty());
    for (const ObjectErrorRow& r : info.rows[t]) expectSameStats(r.stats, f.evaluation.term(Term::Direct).perObject[size_t(r.objectId)]);

    const std::string csv = objectRowsCsv(info.rows[t], "direct");
    const std::string header = csv.substr(0, csv.find('\n'));
    EXPECT_NE(header.find(",rmse_noise_floor,rmse_corrected,relative_rmse_noise_floor,relative_rmse_corrected"), std::string::npos);
    const ErrorStats& first = info.rows[t].front().stats;
    char floor[32];
    std::snprintf(floor, sizeof floor, ",%.9g,", first.relativeRmseNoiseFloor);
    const std::string firstLine = csv.substr(header.size() + 1, csv.find('\n', header.size() + 1) - header.size() - 1);
    EXPECT_NE(firstLine.find(floor), std::string::npos) << firstLine;

    ObjectErrorRow unknown;
    unknown.objectId = 0;
    unknown.name = "wall";
    unknown.stats.rmse = 0.1;
    const std::string u = objectRowsCsv({unknown}, "global");
    // rmse/relative floor and corrected, then bias 0, relMSE 0, its floor and corrected, SMAPE 0, no FLIP.
    EXPECT_EQ(u.substr(u.size() - 13), ",,,,0,0,,,0,\n") << "unknown noise and FLIP columns are empty, never 0: " << u;
}

// Issue 30 item 6: a region's figures are errorStatsWithNoise over the mask's kept pixels inside it
// (all metrics, with the ground truth's noise), recomputed when the region moves.
TEST(HonestFigures, RegionFiguresAreThoseOfItsKeptPixels) {
    const Fixture f;
    WorkbenchState s;
    f.fill(s);
    s.view.region = {4, 6, 16, 14};
    ViewModel vm;
    vm.update(s);
    ASSERT_TRUE(s.view.regionStats.valid);
    std::vector<uint32_t> px;
    for (uint32_t i : f.mask->kept)
        if (int(i % kSize) >= 4 && int(i % kSize) < 16 && int(i / kSize) >= 6 && int(i / kSize) < 14) px.push_back(i);
    ASSERT_FALSE(px.empty());
    ASSERT_LT(px.size(), f.mask->kept.size());
    const Term t = s.view.term;
    expectSameStats(s.view.regionStats.stats,
                    errorStatsWithNoise(f.evaluation.prediction.image(t), f.reference.image(t), f.reference.variance(t), px));
    EXPECT_EQ(s.view.regionStats.stats.pixels, px.size());
    s.view.region = {0, 0, 1, 1};  // a corner: background only
    vm.update(s);
    EXPECT_FALSE(s.view.regionStats.valid) << "no kept pixel inside";
    s.view.region = {};
    vm.update(s);
    EXPECT_FALSE(s.view.regionStats.valid);
}

// Issue 30 item 7: the error histogram's bins are log-spaced (four per decade from 1e-5), counted by
// |value| over the given pixels; zeros and values under 1e-5 go below, 10 and over above.
TEST(HonestFigures, ErrorHistogramCountsEachValueInItsLogBin) {
    Image map(8, 1);
    const float values[8] = {0.f, 1e-6f, 1e-5f, 0.012f, -0.012f, 0.5f, 20.f, std::nanf("")};
    for (int x = 0; x < 8; ++x) map.set(x, 0, Vec3(values[x]));
    const ErrorHistogram h = errorHistogram(map, nullptr);
    ASSERT_EQ(h.counts.size(), 24u);
    EXPECT_GE(h.below, 2u) << "0 and 1e-6 (and 1e-5f if it rounds under the edge)";
    EXPECT_EQ(h.above, 1u) << "20";
    EXPECT_EQ(h.negative, 1u);
    EXPECT_EQ(h.total(), 7u) << "the NaN is left out";
    // 1e-5 opens bin 0 (rounding may put it at the top of the bin below: 1e-5f is not exact).
    EXPECT_EQ(h.counts[0] + h.below, 3u);
    // log10(0.012) = -1.92: (−1.92 + 5) · 4 = 12.3, bin 12, for both signs.
    EXPECT_EQ(h.counts[12], 2u);
    // log10(0.5) = -0.30: (−0.30 + 5) · 4 = 18.8, bin 18.
    EXPECT_EQ(h.counts[18], 1u);
    const std::vector<uint32_t> some = {3, 5};
    const ErrorHistogram m = errorHistogram(map, &some);
    EXPECT_EQ(m.total(), 2u);
    EXPECT_EQ(m.counts[12], 1u);
    EXPECT_EQ(m.counts[18], 1u);
}

// Issue 30 item 3: the Views' FLIP map is shown only when it was computed from the images on screen
// (the workbench computes it on a worker), in magma; a newer prediction hides the older map.
TEST(HonestFigures, FlipViewShowsOnlyTheMapOfTheImagesOnScreen) {
    const Fixture f;
    WorkbenchState s;
    f.fill(s);
    s.view.flip = true;
    ViewModel vm;
    vm.update(s);
    EXPECT_TRUE(vm.image(ViewModel::kError).rgba.empty()) << "no FLIP map yet: nothing shown";

    FlipViewMap m;
    m.groundTruth = s.groundTruth.revision;
    m.compared = s.prediction.revision;
    m.term = s.view.term;
    const Image& ref = f.reference.image(s.view.term);
    m.range = flipExposureRange(ref);
    m.map = hdrFlip(ref, f.evaluation.prediction.image(s.view.term), m.range);
    m.revision = 1;
    s.view.flipMap = m;
    vm.update(s);
    ASSERT_FALSE(vm.image(ViewModel::kError).rgba.empty());
    ASSERT_EQ(vm.error().data, m.map.data) << "the error view shows the FLIP map";
    // A kept pixel is drawn in magma (the FLIP tools' map), not in viridis.
    ASSERT_FALSE(f.mask->kept.empty());
    const size_t i = f.mask->kept.front();
    const Vec3 c = magma(m.map.data[3 * i]);
    const uint8_t* px = &vm.image(ViewModel::kError).rgba[4 * i];
    EXPECT_NEAR(px[0], std::lround(linearToSrgb(std::min(c.x, 1.f)) * 255.f), 1);
    EXPECT_NEAR(px[2], std::lround(linearToSrgb(std::min(c.z, 1.f)) * 255.f), 1);

    s.prediction.touch();  // a newer prediction: the map is of the old one
    vm.update(s);
    EXPECT_TRUE(vm.image(ViewModel::kError).rgba.empty());
    s.view.flip = false;  // the per-pixel metrics need no worker
    vm.update(s);
    EXPECT_FALSE(vm.image(ViewModel::kError).rgba.empty());
}

// The Objects table's FLIP column is evaluate()'s per-object HDR-FLIP (global term only), and the
// header's figures its overall mean and noise floor.
TEST(HonestFigures, ObjectsTableCarriesTheFlipOfEachObject) {
    Fixture f;
    f.evaluation.flip = flipEvaluation(f.evaluation, f.reference);
    ASSERT_TRUE(f.evaluation.flip.available);
    const EvaluationInfo info = evaluationInfo(f.evaluation, f.scene, f.models);
    EXPECT_EQ(info.flipHdr, f.evaluation.flip.hdr.mean);
    EXPECT_EQ(info.flipNoiseFloor, f.evaluation.flip.hdrNoiseFloor);
    EXPECT_TRUE(std::isfinite(info.flipNoiseFloor)) << "the ground truth carries its variance";
    size_t withFlip = 0;
    for (const ObjectErrorRow& r : info.rows[int(Term::Global)]) {
        const FlipStats& o = f.evaluation.flip.hdrPerObject[size_t(r.objectId)];
        if (o.pixels) {
            EXPECT_EQ(r.flip, o.mean);
            ++withFlip;
        } else {
            EXPECT_TRUE(std::isnan(r.flip));
        }
    }
    EXPECT_GT(withFlip, 0u);
    for (const ObjectErrorRow& r : info.rows[int(Term::Direct)]) EXPECT_TRUE(std::isnan(r.flip)) << "global term only";
    const std::string csv = objectRowsCsv(info.rows[int(Term::Global)], "global");
    char first[40];
    std::snprintf(first, sizeof first, ",%.9g\n", info.rows[int(Term::Global)].front().flip);
    if (!std::isnan(info.rows[int(Term::Global)].front().flip)) {
        EXPECT_NE(csv.find(first), std::string::npos) << csv;
    }
}

TEST_F(CostPanelTest, CostPanelDrawsTwoSeriesAndTheBreakEven) {
    WorkbenchState s;
    s.hasProject = true;
    s.cost.sweeps = twoSeries();
    for (int i = 0; i < 2; ++i) frame([&] { drawCostPanel(costPanelView(s)); });
    EXPECT_TRUE(s.requests.empty());
    const std::vector<std::string>& lines = s.costView.breakEvenLines;
    ASSERT_EQ(lines.size(), 2u);
    // 0.1 = 0.8/√N  ⇒  N = 64 spp, 0.64 s; 0.2 ⇒ N = 16 spp, 0.16 s.
    EXPECT_EQ(lines[0], "sweep hidden 20,10: the path tracer needs 64 spp / 0.64 s to reach this model's error (0.1, corrected); "
                        "the model needs 2.5 ms per frame (CPU), 0.4 ms (GLSL)");
    EXPECT_NE(lines[1].find("needs 16 spp / 0.16 s"), std::string::npos) << lines[1];
    EXPECT_LT(s.costView.plotMinX, s.costView.plotMaxX);

    // A model series whose path tracer is not shown has no break-even, and says so.
    s.cost.sweeps.erase(s.cost.sweeps.begin());
    frame([&] { drawCostPanel(costPanelView(s)); });
    ASSERT_EQ(s.costView.breakEvenLines.size(), 2u);
    EXPECT_NE(s.costView.breakEvenLines[0].find("no path-tracer series"), std::string::npos);
}

TEST_F(CostPanelTest, SeriesColoursFollowTheirNames) {
    const std::vector<CostSeries> two = twoSeries();
    const ImU32 pt = seriesColour(two[0].name), models = seriesColour(two[1].name);
    EXPECT_NE(pt, models) << "a sweep's models and its path tracer are told apart";
    // Neither is the colour of a series index, so drawing by index would be caught below.
    for (int i = 0; i < 2; ++i) EXPECT_TRUE(seriesColour(i) != pt && seriesColour(i) != models) << i;
    // Whatever the order of the series, the panel draws each in its name's colour.
    for (bool reversed : {false, true}) {
        WorkbenchState s;
        s.cost.sweeps = two;
        if (reversed) std::swap(s.cost.sweeps[0], s.cost.sweeps[1]);
        frame([&] { drawCostPanel(costPanelView(s)); });
        EXPECT_TRUE(drawListsHoldColour(pt)) << reversed;
        EXPECT_TRUE(drawListsHoldColour(models)) << reversed;
        EXPECT_EQ(seriesColour(two[0].name), pt) << "a function of the name alone";
    }
}

}  // namespace rrf::test::test_honest_figures

namespace test_honest_figures_spread {
using namespace rrf;
using namespace rrf::panels;

TEST(HonestFigures, ObjectsHeaderCarriesTheEnsembleSpreadsRankCorrelation) {
    // The Objects panel's uncertainty line reads evaluate()'s figures: overall and per visible object.
    Scene scene;
    scene.objects.resize(2);
    scene.objects[0].name = "floor";
    scene.objects[1].name = "box";
    Evaluation e;
    EXPECT_TRUE(std::isnan(evaluationInfo(e, scene, ModelSet()).spreadSpearman));
    e.uncertainty.available = true;
    e.uncertainty.overall = {10, 0.02, 0.05, 0.61};
    e.uncertainty.perObject = {{6, 0.01, 0.04, 0.7}, {0, 0, 0, std::nan("")}};
    const EvaluationInfo info = evaluationInfo(e, scene, ModelSet());
    EXPECT_DOUBLE_EQ(info.spreadSpearman, 0.61);
    EXPECT_DOUBLE_EQ(info.spreadRelative, 0.02);
    ASSERT_EQ(info.spreadSpearmanPerObject.size(), 1u);  // the box has no pixels
    EXPECT_EQ(info.spreadSpearmanPerObject[0].first, "floor");
    EXPECT_DOUBLE_EQ(info.spreadSpearmanPerObject[0].second, 0.7);
}
}  // namespace test_honest_figures_spread

namespace test_honest_figures_spread_view {
using namespace rrf;
using namespace rrf::panels;

TEST(HonestFigures, SpreadViewShowsOnlyTheMapOfThePredictionOnScreen) {
    WorkbenchState s;
    s.prediction.global = Image(4, 2);
    for (int x = 0; x < 4; ++x) s.prediction.global.set(x, 0, Vec3(0.5f));
    s.prediction.touch();
    ViewModel vm;
    vm.update(s);
    const std::vector<uint8_t> plain = vm.image(ViewModel::kCompared).rgba;
    s.view.spread = true;
    SpreadViewMap m;
    m.prediction = s.prediction.revision;
    m.map = Image(4, 2);
    m.map.set(3, 1, Vec3(0.2f));
    m.scale = 0.2f;
    m.pixels = 8;
    m.revision = 1;
    s.view.spreadMap = m;
    EXPECT_TRUE(spreadShown(s));
    vm.update(s);
    const std::vector<uint8_t>& shown = vm.image(ViewModel::kCompared).rgba;
    ASSERT_EQ(shown.size(), plain.size());
    EXPECT_NE(shown, plain);
    // Pixel (3, 1) at the top of the scale: viridis's yellow end (red and green high, blue low).
    const size_t i = (size_t(1) * 4 + 3) * 4;
    EXPECT_GT(shown[i], 200);
    EXPECT_GT(shown[i + 1], 200);
    EXPECT_LT(shown[i + 2], 100);
    // A new prediction: the map belongs to the old one and is not shown.
    s.prediction.touch();
    EXPECT_FALSE(spreadShown(s));
    vm.update(s);
    EXPECT_EQ(vm.image(ViewModel::kCompared).rgba, plain);
}
}  // namespace test_honest_figures_spread_view
