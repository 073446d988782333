#include "core/eval/break_even.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rrf {

double comparableError(const ErrorStats& s) {
    return std::isnan(s.relativeRmseCorrected) ? s.relativeRmse : s.relativeRmseCorrected;
}

BreakEven breakEven(std::vector<PathTracerPoint> series, double error) {
    BreakEven b;
    series.erase(std::remove_if(series.begin(), series.end(),
                                [](const PathTracerPoint& p) { return !(p.spp > 0 && p.seconds > 0 && p.error > 0); }),
                 series.end());
    if (series.size() < 2 || !(error > 0) || !std::isfinite(error)) return b;
    std::stable_sort(series.begin(), series.end(), [](const PathTracerPoint& a, const PathTracerPoint& c) { return a.spp < c.spp; });
    const double le = std::log(error);
    // Between two measured points: the power law through them (exact for error = c·spp^k).
    for (size_t i = 0; i + 1 < series.size(); ++i) {
        const PathTracerPoint& p = series[i];
        const PathTracerPoint& q = series[i + 1];
        const double lp = std::log(p.error), lq = std::log(q.error);
        if (le < std::min(lp, lq) || le > std::max(lp, lq)) continue;
        const double t = lq != lp ? (le - lp) / (lq - lp) : 0.0;
        b.known = true;
        b.spp = std::exp(std::log(p.spp) + t * (std::log(q.spp) - std::log(p.spp)));
        b.seconds = std::exp(std::log(p.seconds) + t * (std::log(q.seconds) - std::log(p.seconds)));
        return b;
    }
    // Outside the measured range: the least-squares line log error = a + k log spp, extended. Render
    // time grows in proportion to the samples, so seconds scale from the nearer end of the series.
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = double(series.size());
    for (const PathTracerPoint& p : series) {
        const double x = std::log(p.spp), y = std::log(p.error);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double den = n * sxx - sx * sx;
    if (den <= 0) return b;
    const double k = (n * sxy - sx * sy) / den;
    const double a = (sy - k * sx) / n;
    if (!(k < 0)) return b;  // the series does not converge: no spp reaches a lower error
    b.known = true;
    b.extrapolated = true;
    b.spp = std::exp((le - a) / k);
    const PathTracerPoint& end = error < series.back().error ? series.back() : series.front();
    b.seconds = end.seconds * b.spp / end.spp;
    return b;
}

std::string breakEvenText(const BreakEven& b, double error, bool corrected, double cpuFrameSeconds,
                          double glslFrameSeconds) {
    char buf[320];
    std::string s;
    const char* kind = corrected ? "corrected" : "raw";
    if (!(error > 0)) {
        std::snprintf(buf, sizeof buf, "this model's error (%s) is at the reference's noise floor: not measurable against it", kind);
        s = buf;
    } else if (!b.known) {
        std::snprintf(buf, sizeof buf, "no path-tracer series reaches this model's error (%.3g, %s)", error, kind);
        s = buf;
    } else {
        std::snprintf(buf, sizeof buf, "the path tracer needs %s%.*f spp / %.3g s to reach this model's error (%.3g, %s)",
                      b.extrapolated ? "~" : "", b.spp < 10 ? 1 : 0, b.spp, b.seconds, error, kind);
        s = buf;
        if (b.extrapolated) s += " (beyond the measured spp, on the fitted log-log line)";
    }
    const bool cpu = std::isfinite(cpuFrameSeconds), glsl = std::isfinite(glslFrameSeconds);
    if (cpu || glsl) {
        s += "; the model needs ";
        if (cpu) {
            std::snprintf(buf, sizeof buf, "%.3g ms per frame (CPU)", 1e3 * cpuFrameSeconds);
            s += buf;
        }
        if (glsl) {
            std::snprintf(buf, sizeof buf, "%s%.3g ms%s (GLSL)", cpu ? ", " : "", 1e3 * glslFrameSeconds, cpu ? "" : " per frame");
            s += buf;
        }
    }
    return s;
}

}  // namespace rrf
