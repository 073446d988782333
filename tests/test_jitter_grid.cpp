// Jitter grid and viewpoint classifier of the data generator: one uniformly random viewpoint inside
// each cell, a pure function of (cell, seed); viewpoints inside closed objects (the Cornell box's
// blocks, a sphere) are dropped, open-air ones kept, far-away ones are outside the scene; and the
// generator drops exactly the cells the classifier rejects.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/data/data_generator.h"
#include "core/data/dataset_header_json.h"
#include "core/data/jitter_grid.h"
#include "core/project/project.h"
#include "core/project/project_file.h"
#include "scene_builders.h"

namespace test_jitter_grid {

using namespace rrf;
using namespace rrf::test;

namespace {

Project cornellBox() { return loadProjectOrScene(std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json"); }

const char* statusName(ViewpointStatus s) {
    switch (s) {
        case ViewpointStatus::Kept: return "Kept";
        case ViewpointStatus::InsideObject: return "InsideObject";
        case ViewpointStatus::OutsideScene: return "OutsideScene";
        case ViewpointStatus::BehindSurface: return "BehindSurface";
    }
    return "?";
}

/// Classifies `p` in `scene` (builds the BVH and a tracer for it).
struct Classifier {
    explicit Classifier(const Scene& scene) : accel(scene), tracer(scene, accel, Estimator::NEE), classifier(tracer) {}
    ViewpointStatus operator()(const Vec3& p) const { return classifier.classify(p); }
    Accel accel;
    PathTracer tracer;
    ViewpointClassifier classifier;
};

// Cornell box blocks (projects/cornell-box/scene.json): unit boxes scaled, rotated about y by
// −17° / 18.25° and translated. Points within the inscribed cylinder of radius 0.3 (half the 0.6
// scale) about the vertical axis are inside whatever the rotation; points more than 0.3·√2 ≈ 0.43
// from it are outside.
const Vec3 kShortBox(0.335f, -0.7f, 0.38f);   // y ∈ [−1.0, −0.4]
const Vec3 kTallBox(-0.33f, -0.4f, -0.28f);   // y ∈ [−1.01, 0.21]

}  // namespace

TEST(JitterGrid, ViewpointsLieInsideTheirCells) {
    Bounds3 b;
    b.expand(Vec3(-1.5f, 0.25f, -3.f));
    b.expand(Vec3(2.5f, 1.75f, 5.f));
    const int nx = 4, ny = 3, nz = 5;
    const JitterGrid grid(b, nx, ny, nz);
    ASSERT_EQ(grid.cellCount(), nx * ny * nz);
    const Vec3 e = b.extent();
    // Float rounding of lo + e·(i + u)/n can land a few ulps past a cell face; 1e-5 of the extent
    // is far below any cell size and far above the rounding.
    const float tol = 1e-5f * e.maxComponent();
    for (uint64_t seed : {1ull, 2ull, 12345ull}) {
        for (int cell = 0; cell < grid.cellCount(); ++cell) {
            int ix, iy, iz;
            grid.cellCoords(cell, ix, iy, iz);
            ASSERT_EQ(cell, ix + nx * (iy + ny * iz)) << "x fastest";
            const Vec3 p = grid.viewpoint(cell, seed);
            const Vec3 lo(b.lo.x + e.x * float(ix) / float(nx), b.lo.y + e.y * float(iy) / float(ny),
                          b.lo.z + e.z * float(iz) / float(nz));
            const Vec3 hi(b.lo.x + e.x * float(ix + 1) / float(nx), b.lo.y + e.y * float(iy + 1) / float(ny),
                          b.lo.z + e.z * float(iz + 1) / float(nz));
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(p[c], lo[c] - tol) << "cell " << cell << " axis " << c << " seed " << seed;
                EXPECT_LE(p[c], hi[c] + tol) << "cell " << cell << " axis " << c << " seed " << seed;
            }
            // A pure function of (cell, seed): thread count and sharding cannot change it.
            const Vec3 again = grid.viewpoint(cell, seed);
            EXPECT_TRUE(p.x == again.x && p.y == again.y && p.z == again.z);
        }
    }
    // Another seed moves the viewpoints.
    EXPECT_NE(grid.viewpoint(7, 1).x, grid.viewpoint(7, 2).x);
}

TEST(JitterGrid, ViewpointsAreUniformWithinCells) {
    // Relative position of each viewpoint in its cell, per axis: i.i.d. U(0,1) over the cells, so
    // the mean is 1/2 with standard error sqrt(1/12 / N), and each quarter of [0,1) holds N/4 ± 5σ
    // with σ = sqrt(N · 1/4 · 3/4).
    Bounds3 b;
    b.expand(Vec3(0.f));
    b.expand(Vec3(10.f, 20.f, 30.f));
    const int n = 16;
    const JitterGrid grid(b, n, n, n);
    const int cells = grid.cellCount();
    const double sigmaMean = std::sqrt(1.0 / 12.0 / cells);
    const double sigmaQuarter = std::sqrt(cells * 0.25 * 0.75);
    for (int c = 0; c < 3; ++c) {
        double sum = 0;
        int quarters[4] = {0, 0, 0, 0};
        for (int cell = 0; cell < cells; ++cell) {
            int idx[3];
            grid.cellCoords(cell, idx[0], idx[1], idx[2]);
            const Vec3 p = grid.viewpoint(cell, 99);
            const double f = (double(p[c]) - b.lo[c]) / b.extent()[c] * n - idx[c];
            sum += f;
            ++quarters[std::min(3, std::max(0, int(f * 4)))];
        }
        EXPECT_NEAR(sum / cells, 0.5, 5 * sigmaMean) << "axis " << c;
        for (int q = 0; q < 4; ++q) EXPECT_NEAR(quarters[q], cells / 4.0, 5 * sigmaQuarter) << "axis " << c << " quarter " << q;
    }
}

TEST(ViewpointClassifier, CornellBoxBlocksAreDroppedAndOpenAirIsKept) {
    const Project project = cornellBox();
    const Scene& scene = project.scene;
    int closed = 0;
    for (const Object& o : scene.objects) closed += o.closed;
    ASSERT_EQ(closed, 2) << "the two blocks are the only closed objects";
    const Classifier classify(scene);

    struct Case {
        Vec3 p;
        ViewpointStatus expected;
        const char* what;
    };
    const std::vector<Case> cases = {
        {kShortBox, ViewpointStatus::InsideObject, "short box centre"},
        {kShortBox + Vec3(0.25f, 0.25f, 0.f), ViewpointStatus::InsideObject, "short box, near its top"},
        {kShortBox + Vec3(-0.2f, -0.25f, 0.15f), ViewpointStatus::InsideObject, "short box, near the floor"},
        {kShortBox + Vec3(0.f, 0.35f, 0.f), ViewpointStatus::Kept, "just above the short box"},
        {kShortBox + Vec3(0.45f, 0.f, 0.f), ViewpointStatus::Kept, "beside the short box"},
        {kTallBox, ViewpointStatus::InsideObject, "tall box centre"},
        {kTallBox + Vec3(0.f, 0.55f, 0.2f), ViewpointStatus::InsideObject, "tall box, near its top"},
        {kTallBox + Vec3(-0.2f, -0.55f, -0.2f), ViewpointStatus::InsideObject, "tall box, near the floor"},
        {kTallBox + Vec3(0.f, 0.66f, 0.f), ViewpointStatus::Kept, "just above the tall box"},
        {kTallBox + Vec3(0.f, 0.f, 0.45f), ViewpointStatus::Kept, "in front of the tall box"},
        {Vec3(0.f, 0.3f, 0.f), ViewpointStatus::Kept, "room centre, under the light"},
        {Vec3(0.9f, 0.9f, -0.9f), ViewpointStatus::Kept, "back top corner"},
        {Vec3(-0.9f, -0.9f, 0.9f), ViewpointStatus::Kept, "front floor corner by the open side"},
        {Vec3(0.f, 0.f, 50.f), ViewpointStatus::OutsideScene, "far in front of the open side"},
        {Vec3(0.f, 10.f, 0.f), ViewpointStatus::OutsideScene, "far above the ceiling"},
        {Vec3(-40.f, -30.f, -20.f), ViewpointStatus::OutsideScene, "far behind and below"},
    };
    for (const Case& c : cases) {
        const ViewpointStatus got = classify(c.p);
        EXPECT_EQ(got, c.expected) << c.what << " at " << c.p << ": got " << statusName(got) << ", expected "
                                   << statusName(c.expected);
    }
}

TEST(ViewpointClassifier, ClosedSphereIsDroppedOpenObjectsAreNot) {
    // A closed room made of inward-facing quads (not flagged closed: the room is where viewpoints
    // should be), a closed sphere, and an open box (the same faces, not flagged closed) inside it.
    Scene s;
    const int m = addLambert(s, Vec3(0.5f));
    addQuads(s, inwardCubeFaces(2.f), m, "room");
    Object sphere;
    sphere.kind = Object::Kind::Sphere;
    sphere.name = "ball";
    sphere.id = int(s.objects.size());
    sphere.material = m;
    sphere.center = Vec3(0.8f, -0.5f, 0.3f);
    sphere.radius = 0.6f;
    sphere.closed = true;
    s.objects.push_back(sphere);
    std::vector<QuadSpec> crate = inwardCubeFaces(0.4f);
    for (QuadSpec& q : crate) q.corner = q.corner + Vec3(-1.f, 1.f, -1.f);
    addQuads(s, crate, m, "open crate");
    addCeilingLight(s, 0.f, 0.f, 1.99f, 0.5f);
    const Classifier classify(s);

    EXPECT_EQ(classify(sphere.center), ViewpointStatus::InsideObject);
    EXPECT_EQ(classify(sphere.center + Vec3(0.f, 0.5f, 0.f)), ViewpointStatus::InsideObject) << "near the pole";
    EXPECT_EQ(classify(sphere.center + Vec3(-0.3f, 0.f, 0.45f)), ViewpointStatus::InsideObject) << "off centre";
    EXPECT_EQ(classify(sphere.center + Vec3(0.f, 0.65f, 0.f)), ViewpointStatus::Kept) << "just above";
    EXPECT_EQ(classify(sphere.center + Vec3(-0.7f, 0.f, 0.f)), ViewpointStatus::Kept) << "just beside";
    EXPECT_EQ(classify(Vec3(-1.f, 1.f, -1.f)), ViewpointStatus::Kept) << "inside the open crate";
    EXPECT_EQ(classify(Vec3(1.5f, 1.5f, 1.5f)), ViewpointStatus::Kept) << "room corner";
    EXPECT_EQ(classify(Vec3(0.f, 0.f, 30.f)), ViewpointStatus::OutsideScene) << "outside the closed room";
}

TEST(ViewpointClassifier, GeneratorDropsExactlyTheCellsTheClassifierRejects) {
    // The Cornell box plus a small card far in front of the open side: the card stretches the scene
    // bounds (and so the grid) into open air, so the run has cells of all three kinds.
    Project project = cornellBox();
    Scene& scene = project.scene;
    addQuads(scene, {{{-0.2f, -0.2f, 5.f}, {0.4f, 0.f, 0.f}, {0.f, 0.4f, 0.f}}}, scene.objects[0].material, "card");
    SamplingSettings settings;
    settings.nx = settings.ny = 6;
    settings.nz = 8;
    settings.directions = 4;
    settings.spp = 1;
    settings.seed = 7;
    const DataGenerator gen(scene, settings);
    const GeneratedData data = gen.run();

    const JitterGrid grid(scene.bounds(), settings.nx, settings.ny, settings.nz);
    const ViewpointClassifier classifier(gen.tracer());
    uint64_t inside = 0, outside = 0;
    const nlohmann::json perCell = datasetHeader(data).at("stats").at("records_per_cell");
    ASSERT_EQ(perCell.size(), size_t(grid.cellCount()));
    for (int cell = 0; cell < grid.cellCount(); ++cell) {
        const ViewpointStatus st = classifier.classify(grid.viewpoint(cell, settings.seed));
        inside += st == ViewpointStatus::InsideObject;
        outside += st == ViewpointStatus::OutsideScene;
        // A dropped cell makes no records.
        if (st != ViewpointStatus::Kept) {
            EXPECT_EQ(perCell[size_t(cell)].get<uint64_t>(), 0u) << "cell " << cell;
        }
    }
    // The test is only meaningful if both kinds of drop occur with this seed and grid.
    EXPECT_GT(inside, 0u);
    EXPECT_GT(outside, 0u);
    EXPECT_EQ(datasetHeader(data).at("stats").at("cells_dropped_inside_object").get<uint64_t>(), inside);
    EXPECT_EQ(datasetHeader(data).at("stats").at("cells_dropped_outside_scene").get<uint64_t>(), outside);
}

TEST(ViewpointClassifier, InsideMeansAnOddNumberOfCrossings) {
    // One closed object made of two nested cubes: the outer [-1.5, 1.5]³ facing out, the inner
    // [-0.5, 0.5]³ facing in (a hollow block with a cavity). From the cavity every probe crosses the
    // object twice (even: open air, kept); from the shell's material once (odd: inside); from far away
    // no probe meets anything (outside the scene). Counting any crossing would drop the cavity.
    Scene s;
    const int m = addLambert(s, Vec3(0.5f));
    std::vector<QuadSpec> faces = inwardCubeFaces(0.5f);
    for (QuadSpec q : inwardCubeFaces(1.5f)) faces.push_back({q.corner + q.e1, -q.e1, q.e2});  // flipped: outwards
    addQuads(s, faces, m, "hollow block");
    s.objects.back().closed = true;
    addCeilingLight(s, 0.f, 0.f, 3.f, 0.5f);
    const Classifier classify(s);
    for (const Vec3 p : {Vec3(0.f), Vec3(0.3f, -0.2f, 0.1f), Vec3(-0.4f, 0.4f, -0.35f)})
        EXPECT_STREQ(statusName(classify(p)), "Kept") << "cavity at " << p;
    for (const Vec3 p : {Vec3(1.f, 0.f, 0.f), Vec3(0.2f, -1.2f, 0.3f), Vec3(1.2f, 1.1f, -1.f)})
        EXPECT_STREQ(statusName(classify(p)), "InsideObject") << "shell at " << p;
    EXPECT_STREQ(statusName(classify(Vec3(0.f, 0.f, 40.f))), "OutsideScene");
}

}  // namespace test_jitter_grid
