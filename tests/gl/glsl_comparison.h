#pragma once
/// Comparisons of the GLSL predictor with the CPU shared by the GL test files: the G-buffer against
/// the CPU's primary rays, and the shader's terms against NetworkModel::predict on exactly the
/// inputs the G-buffer holds (issue 6: max relative difference ≤ 1e-4 on every covered pixel).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "app/gl/glsl_predictor.h"
#include "core/render/path_tracer.h"
#include "core/scene/camera_rays.h"
#include "tests/gl/test_models.h"

namespace rrf::test {

/// The project default of the live view: exact direct light, a few samples per pixel.
inline PredictionSettings liveSettings() {
    PredictionSettings s;
    s.direct = PredictionSettings::Direct::Exact;
    s.directSamples = 8;
    s.seed = 3;
    return s;
}

/// Largest |a - b| relative to max(|a|, |b|, 1e-3) over every pixel and channel of two images of
/// one size (a size mismatch fails the test).
inline double maxRelativeDifference(const Image& a, const Image& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    double worst = 0.0;
    for (int y = 0; y < std::min(a.height, b.height); ++y)
        for (int x = 0; x < std::min(a.width, b.width); ++x) {
            const Vec3 p = a.at(x, y), q = b.at(x, y);
            for (int c = 0; c < 3; ++c) {
                const double d = std::fabs(double(p[c]) - double(q[c]));
                worst = std::max(worst, d / std::max({std::fabs(double(p[c])), std::fabs(double(q[c])), 1e-3}));
            }
        }
    return worst;
}

struct GBufferComparison {
    size_t pixels = 0, idMismatches = 0, idMismatchesOffSilhouette = 0, compared = 0;
    double maxPositionError = 0, maxNormalError = 0;
};

/// G-buffer vs the CPU's pixel-centre primary rays (CameraRays jitter 0.5, PathTracer::intersect,
/// which includes the movable light). Ids must agree except at silhouettes (pixels whose CPU id differs
/// from a 4-neighbour's: there the rasteriser's and Embree's edge rules may pick different sides).
inline GBufferComparison compareGBuffer(const Scene& scene, const GlGBuffer& g) {
    const Accel accel(scene);
    const PathTracer tracer(scene, accel, Estimator::NEE);
    const CameraRays rays(scene.camera, g.width, g.height);
    std::vector<int> cpuId(g.pixelCount());
    std::vector<Hit> hits(g.pixelCount());
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            Hit h;
            const size_t i = size_t(y) * size_t(g.width) + size_t(x);
            cpuId[i] = tracer.intersect(rays.generate(x, y, 0.5f, 0.5f), h)
                           ? (h.object >= 0 ? h.object : GlGBuffer::kLightPixel)
                           : GlGBuffer::kBackgroundPixel;
            hits[i] = h;
        }
    GBufferComparison c;
    c.pixels = g.pixelCount();
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const size_t i = size_t(y) * size_t(g.width) + size_t(x);
            if (cpuId[i] != g.objectId[i]) {
                ++c.idMismatches;
                bool silhouette = false;
                const int nb[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
                for (const auto& d : nb) {
                    const int nx = x + d[0], ny = y + d[1];
                    if (nx < 0 || ny < 0 || nx >= g.width || ny >= g.height) continue;
                    silhouette |= cpuId[size_t(ny) * size_t(g.width) + size_t(nx)] != cpuId[i];
                }
                if (!silhouette) ++c.idMismatchesOffSilhouette;
                continue;
            }
            if (cpuId[i] == GlGBuffer::kBackgroundPixel) continue;
            ++c.compared;
            const Hit& h = hits[i];
            const Vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
            c.maxPositionError = std::max(c.maxPositionError, double(length(p - h.p)));
            if (cpuId[i] >= 0) {
                const Vec3 wo = -rays.generate(x, y, 0.5f, 0.5f).dir;
                const Vec3 ns = h.shading();                    // vertex normals where the mesh has them
                const Vec3 n = dot(wo, ns) >= 0.f ? ns : -ns;  // core/predict/gbuffer.cpp's convention
                const Vec3 gn(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
                c.maxNormalError = std::max(c.maxNormalError, double(length(gn - n)));
            }
        }
    return c;
}

struct PredictionComparison {
    size_t covered = 0, objectPixels = 0, lightPixels = 0, failures = 0;
    double maxRelative = 0;  ///< max |gl − cpu| / max(|cpu|, 1e-2) over all channels and terms
    /// The same measure for the CPU's float prediction against its double prediction: the float
    /// noise floor of these networks, which no float implementation can beat.
    double floatVsDouble = 0;
    double glVsDouble = 0;
    std::string firstFailure;
};

/// Feeds exactly the G-buffer's inputs to NetworkModel::predict and compares every covered pixel.
inline PredictionComparison comparePrediction(const Scene& scene, const ModelSet& set, const GlslPredictor& gp) {
    const GlGBuffer g = gp.readGBuffer();
    const Image gl[3] = {gp.read(Term::Direct), gp.read(Term::Indirect),
                         gp.read(Term::Global)};
    const RecordLayout layout = RecordLayout::forScene(scene);
    const Vec3 eye = scene.camera.eye, light = gp.lightPosition();
    PredictionComparison r;
    auto check = [&](int term, int x, int y, const Vec3& cpu) {
        const Vec3 v = gl[term].at(x, y);
        for (int ch = 0; ch < 3; ++ch) {
            const double rel = std::fabs(double(v[ch]) - double(cpu[ch])) / std::max(std::fabs(double(cpu[ch])), 1e-2);
            r.maxRelative = std::max(r.maxRelative, rel);
            if (!closeEnough(v[ch], cpu[ch])) {
                if (r.failures++ == 0) {
                    char b[256];
                    std::snprintf(b, sizeof b, "pixel (%d,%d) %s channel %d: GLSL %.9g CPU %.9g", x, y,
                                  termName(Term(term)), ch, double(v[ch]), double(cpu[ch]));
                    r.firstFailure = b;
                }
            }
        }
    };
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const int id = g.objectId[size_t(y) * size_t(g.width) + size_t(x)];
            if (id == GlGBuffer::kBackgroundPixel) {
                for (int t = 0; t < 3; ++t) check(t, x, y, Vec3(0.f));
            } else if (id == GlGBuffer::kLightPixel) {
                ++r.covered;
                ++r.lightPixels;
                const Vec3 e = g.emission.at(x, y);
                check(0, x, y, e);
                check(1, x, y, Vec3(0.f));
                check(2, x, y, e);
            }
        }
    for (const ObjectNetworks& on : set.objects) {
        std::vector<std::pair<int, int>> px;
        for (int y = 0; y < g.height; ++y)
            for (int x = 0; x < g.width; ++x)
                if (g.objectId[size_t(y) * size_t(g.width) + size_t(x)] == on.objectId) px.emplace_back(x, y);
        if (px.empty()) continue;
        float brdf[8] = {};
        layout.brdfParameters(scene.materials[size_t(scene.objects[size_t(on.objectId)].material)], brdf);
        MatX<float> raw(layout.inputCount(), Eigen::Index(px.size()));
        for (size_t k = 0; k < px.size(); ++k) {
            const size_t i = size_t(px[k].second) * size_t(g.width) + size_t(px[k].first);
            const Vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
            const Vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
            const Vec3 f[4] = {p, normalize(eye - p), light, n};
            for (int j = 0; j < 12; ++j) raw(j, Eigen::Index(k)) = f[j / 3][j % 3];
            for (int j = 12; j < layout.inputCount(); ++j) raw(j, Eigen::Index(k)) = brdf[j - 12];
        }
        const test::CpuTerms cpu = test::cpuTerms(on, raw);
        const MatX<double> rawD = raw.cast<double>();
        const test::CpuTermsT<double> exact = test::cpuTerms(on, rawD);
        const MatX<float>* terms[3] = {&cpu.direct, &cpu.indirect, &cpu.global};
        const MatX<double>* exactTerms[3] = {&exact.direct, &exact.indirect, &exact.global};
        for (size_t k = 0; k < px.size(); ++k)
            for (int t = 0; t < 3; ++t) {
                const auto& m = *terms[t];
                const Eigen::Index c = Eigen::Index(k);
                check(t, px[k].first, px[k].second, Vec3(m(0, c), m(1, c), m(2, c)));
                const Vec3 v = gl[t].at(px[k].first, px[k].second);
                for (int ch = 0; ch < 3; ++ch) {
                    const double e = (*exactTerms[t])(ch, c), den = std::max(std::fabs(e), 1e-2);
                    r.floatVsDouble = std::max(r.floatVsDouble, std::fabs(double(m(ch, c)) - e) / den);
                    r.glVsDouble = std::max(r.glVsDouble, std::fabs(double(v[ch]) - e) / den);
                }
            }
        r.covered += px.size();
        r.objectPixels += px.size();
    }
    return r;
}

inline void expectEquivalent(const Scene& scene, const ModelSet& set, const GlslPredictor& gp, double minCoveredFraction) {
    const PredictionComparison r = comparePrediction(scene, set, gp);
    const size_t pixels = size_t(gp.width()) * size_t(gp.height());
    std::printf("  light (%.3f %.3f %.3f): %zu covered pixels (%zu object, %zu light); max relative difference "
                "GLSL-CPU %.3g (GLSL-double %.3g, CPU float-double %.3g)\n",
                double(gp.lightPosition().x), double(gp.lightPosition().y), double(gp.lightPosition().z), r.covered,
                r.objectPixels, r.lightPixels, r.maxRelative, r.glVsDouble, r.floatVsDouble);
    EXPECT_EQ(r.failures, 0u) << "first: " << r.firstFailure << " (max relative " << r.maxRelative << ")";
    EXPECT_GE(double(r.objectPixels), minCoveredFraction * double(pixels));
}

}  // namespace rrf::test
