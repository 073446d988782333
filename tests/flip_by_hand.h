#pragma once
/// FLIP written out independently of core/eval/flip*.cpp, for tests/test_flip.cpp: the paper's
/// formulas for flat fields (HPG 2020 colour metric, Narkowicz's ACES fit as HDR-FLIP uses it) and a
/// direct LDR-FLIP with the 2D kernels built and normalised as 2D arrays, applied by brute force.
/// Slow and plain on purpose: it shares no code with the implementation it checks.

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/util/image.h"

namespace flip_by_hand {

using rrf::Image;
using rrf::Vec3;

// The paper's colour error of two uniform colours, written out from the formulas (HPG 2020) with
// no filtering (a flat field is its own filtered version): sRGB → XYZ (IEC 61966-2-1, white = the
// XYZ of RGB (1, 1, 1)) → CIELAB → Hunt (a, b scaled by L/100) → HyAB → ^0.7 → compression with
// pc = 0.4, pt = 0.95 against cmax = HyAB(green, blue)^0.7.
struct HandLab {
    double L, a, b;
};
inline HandLab handHuntLab(double r, double g, double b) {
    const double X = 0.4124 * r + 0.3576 * g + 0.1805 * b;
    const double Y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    const double Z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
    const double Xn = 0.4124 + 0.3576 + 0.1805, Yn = 0.2126 + 0.7152 + 0.0722, Zn = 0.0193 + 0.1192 + 0.9505;
    auto f = [](double t) {
        const double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
    };
    const double L = 116 * f(Y / Yn) - 16;
    const double a = 500 * (f(X / Xn) - f(Y / Yn)), bb = 200 * (f(Y / Yn) - f(Z / Zn));
    return {L, a * L / 100, bb * L / 100};
}
inline double handHyab(const HandLab& p, const HandLab& q) {
    return std::fabs(p.L - q.L) + std::sqrt((p.a - q.a) * (p.a - q.a) + (p.b - q.b) * (p.b - q.b));
}
inline double handColourError(const Vec3& p, const Vec3& q) {
    const double cmax = std::pow(handHyab(handHuntLab(0, 1, 0), handHuntLab(0, 0, 1)), 0.7);
    const double d = std::pow(handHyab(handHuntLab(p.x, p.y, p.z), handHuntLab(q.x, q.y, q.z)), 0.7);
    if (d < 0.4 * cmax) return 0.95 * d / (0.4 * cmax);
    return 0.95 + 0.05 * (d - 0.4 * cmax) / (0.6 * cmax);
}

// Narkowicz's published ACES fit, applied to 0.6 x as HDR-FLIP does, and the x it maps to 0.85
// found by bisection (the curve is increasing).
inline double handAces(double x) {
    x *= 0.6;
    return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
}
inline double handX85() {
    double lo = 0, hi = 100;
    for (int i = 0; i < 200; ++i) (handAces(0.5 * (lo + hi)) < 0.85 ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
}

// LDR-FLIP written the direct way, for comparison: the paper's 2D kernels built and normalised
// as 2D arrays (no separable factoring), applied by brute force with clamp-to-edge, in double.
using Grid = std::vector<double>;
inline Grid bruteFilter(const Grid& in, int w, int h, const Grid& k, int r) {
    Grid out(in.size(), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double acc = 0;
            for (int j = -r; j <= r; ++j)
                for (int i = -r; i <= r; ++i)
                    acc += k[size_t((j + r) * (2 * r + 1) + i + r)] *
                           in[size_t(std::clamp(y + j, 0, h - 1) * w + std::clamp(x + i, 0, w - 1))];
            out[size_t(y * w + x)] = acc;
        }
    return out;
}
inline Image bruteLdrFlip(const Image& ref, const Image& test, double ppd) {
    const int w = ref.width, h = ref.height;
    const double pi = 3.14159265358979323846;
    const double Xn = 0.9505, Zn = 1.089;  // row sums of the sRGB matrix
    const double csf[3][4] = {{1, 0.0047, 0, 1}, {1, 0.0053, 0, 1}, {34.1, 0.04, 13.5, 0.025}};
    const int rc = int(std::ceil(3 * std::sqrt(0.04 / (2 * pi * pi)) * ppd));
    const double sd = 0.5 * 0.082 * ppd;
    const int rf = int(std::ceil(3 * sd));
    auto kernel = [](int r, auto fn) {
        Grid k;
        for (int y = -r; y <= r; ++y)
            for (int x = -r; x <= r; ++x) k.push_back(fn(double(x), double(y)));
        return k;
    };
    Grid lab[2][3], edge[2], point[2];
    const Image* imgs[2] = {&ref, &test};
    for (int n = 0; n < 2; ++n) {
        Grid ycc[3], Y;
        for (int c = 0; c < 3; ++c) ycc[c].resize(size_t(w * h));
        for (int p = 0; p < w * h; ++p) {
            double rgb[3];
            for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(double(imgs[n]->data[size_t(3 * p + c)]), 0.0, 1.0);
            const double X = 0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2];
            const double Yv = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
            const double Z = 0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2];
            ycc[0][size_t(p)] = 116 * Yv - 16;
            ycc[1][size_t(p)] = 500 * (X / Xn - Yv);
            ycc[2][size_t(p)] = 200 * (Yv - Z / Zn);
            Y.push_back(Yv);
        }
        for (int c = 0; c < 3; ++c) {
            Grid k = kernel(rc, [&](double x, double y) {
                const double z = (x * x + y * y) / (ppd * ppd);
                const double* q = csf[c];
                return q[0] * std::sqrt(pi / q[1]) * std::exp(-pi * pi * z / q[1]) +
                       q[2] * std::sqrt(pi / q[3]) * std::exp(-pi * pi * z / q[3]);
            });
            double sum = 0;
            for (double v : k) sum += v;
            for (double& v : k) v /= sum;
            ycc[c] = bruteFilter(ycc[c], w, h, k, rc);
        }
        for (int c = 0; c < 3; ++c) lab[n][c].resize(size_t(w * h));
        for (int p = 0; p < w * h; ++p) {
            const double yy = (ycc[0][size_t(p)] + 16) / 116;
            const double X = (yy + ycc[1][size_t(p)] / 500) * Xn, Z = (yy - ycc[2][size_t(p)] / 200) * Zn;
            // XYZ back to linear RGB by solving the 3×3 system (Cramer), then clamp.
            const double M[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
            const double v[3] = {X, yy, Z};
            auto det = [](const double a[3][3]) {
                return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
            };
            double rgb[3];
            for (int c = 0; c < 3; ++c) {
                double A[3][3];
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) A[i][j] = j == c ? v[i] : M[i][j];
                rgb[c] = std::clamp(det(A) / det(M), 0.0, 1.0);
            }
            const HandLab l = handHuntLab(rgb[0], rgb[1], rgb[2]);
            lab[n][0][size_t(p)] = l.L;
            lab[n][1][size_t(p)] = l.a;
            lab[n][2][size_t(p)] = l.b;
        }
        auto g = [&](double x, double y) { return std::exp(-(x * x + y * y) / (2 * sd * sd)); };
        auto normalise = [](Grid k) {
            double pos = 0, neg = 0;
            for (double v : k) (v > 0 ? pos : neg) += v;
            for (double& v : k) v = v > 0 ? v / pos : v / -neg;
            return k;
        };
        const Grid ex = normalise(kernel(rf, [&](double x, double y) { return -x * g(x, y); }));
        const Grid ey = normalise(kernel(rf, [&](double x, double y) { return -y * g(x, y); }));
        const Grid px = normalise(kernel(rf, [&](double x, double y) { return (x * x / (sd * sd) - 1) * g(x, y); }));
        const Grid py = normalise(kernel(rf, [&](double x, double y) { return (y * y / (sd * sd) - 1) * g(x, y); }));
        const Grid fex = bruteFilter(Y, w, h, ex, rf), fey = bruteFilter(Y, w, h, ey, rf);
        const Grid fpx = bruteFilter(Y, w, h, px, rf), fpy = bruteFilter(Y, w, h, py, rf);
        for (int p = 0; p < w * h; ++p) {
            edge[n].push_back(std::hypot(fex[size_t(p)], fey[size_t(p)]));
            point[n].push_back(std::hypot(fpx[size_t(p)], fpy[size_t(p)]));
        }
    }
    const double cmax = std::pow(handHyab(handHuntLab(0, 1, 0), handHuntLab(0, 0, 1)), 0.7);
    Image out(w, h);
    for (int p = 0; p < w * h; ++p) {
        const HandLab a{lab[0][0][size_t(p)], lab[0][1][size_t(p)], lab[0][2][size_t(p)]};
        const HandLab b{lab[1][0][size_t(p)], lab[1][1][size_t(p)], lab[1][2][size_t(p)]};
        const double d = std::pow(handHyab(a, b), 0.7);
        const double ec = d < 0.4 * cmax ? 0.95 * d / (0.4 * cmax) : 0.95 + 0.05 * (d - 0.4 * cmax) / (0.6 * cmax);
        const double df = std::max(std::fabs(edge[0][size_t(p)] - edge[1][size_t(p)]),
                                   std::fabs(point[0][size_t(p)] - point[1][size_t(p)]));
        const double ef = std::sqrt(df / std::sqrt(2.0));
        out.set(p % w, p / w, Vec3(float(std::pow(ec, 1 - ef))));
    }
    return out;
}

}  // namespace flip_by_hand
