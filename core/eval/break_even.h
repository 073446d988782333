#pragma once
/// The break-even between the path tracer and a learned model (docs/design.md §15): how many samples
/// per pixel, and how many seconds, the path tracer needs to reach a model's error against the same
/// reference at the same resolution. Read off the path tracer's own measured series (error against
/// spp and render time, core/pipeline/sweep.h) by interpolation in log-log space, where Monte Carlo
/// error is a straight line (error ∝ spp^−½): between two measured points the power law through them
/// is exact for such a series. Beyond the measured range the least-squares log-log line of the whole
/// series is extended, and the result says so.
///
/// The error compared is the noise-corrected relative RMSE (core/eval/error_metrics.h): the raw one
/// of a good model is mostly the reference's own noise, which would make every model look as good as
/// the path tracer at the reference's spp. Where the reference's noise is unknown the raw figure is
/// used and the text says "raw".

#include <string>
#include <vector>

#include "core/eval/error_metrics.h"

namespace rrf {

/// One measured point of the path tracer's series.
struct PathTracerPoint {
    double spp = 0;      ///< samples per pixel
    double seconds = 0;  ///< render time to reach them (whole image)
    double error = 0;    ///< comparableError() of the image against the reference
};

/// Where the path tracer reaches a given error.
struct BreakEven {
    bool known = false;         ///< false: no usable series (fewer than 2 points with error and time > 0, or
                                ///< no convergence), or the error is not positive (at or below the noise floor)
    double spp = 0, seconds = 0;
    bool extrapolated = false;  ///< outside the measured spp range: the fitted log-log line extended
};

/// The error a cost-of-accuracy comparison uses: the relative RMSE corrected for the reference's
/// noise when that noise is known, else the raw relative RMSE.
double comparableError(const ErrorStats& s);

/// The spp and seconds at which the path tracer's `series` reaches `error`: log-log interpolation
/// between the two measured points that bracket it (the first such pair in spp order), seconds
/// interpolated the same way; outside the range, the least-squares log-log line of error against spp
/// (and seconds proportional to spp). Points with a non-positive spp, time or error are ignored.
BreakEven breakEven(std::vector<PathTracerPoint> series, double error);

/// "the path tracer needs 131 spp / 1.31 s to reach this model's error (0.07, corrected); the model
/// needs 2.1 ms per frame (CPU), 0.4 ms (GLSL)". `corrected`: whether `error` is noise-corrected
/// (else "raw"); a NaN frame time is left out; an unknown break-even is explained instead.
std::string breakEvenText(const BreakEven& b, double error, bool corrected, double cpuFrameSeconds,
                          double glslFrameSeconds);

}  // namespace rrf
