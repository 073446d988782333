#pragma once
/// Error of a prediction against a reference image (docs/design.md §14).
///
/// Conventions (chosen once, used by every report, table and sweep):
///  - Errors are per CHANNEL, averaged over R, G and B (not on luminance): a colour shift the
///    luminance would hide still counts. d = pred − ref per channel.
///  - Per-pixel maps (one scalar per pixel, stored in all three channels):
///      absolute  mean_c |d_c|
///      relative  mean_c |d_c| / (|ref_c| + 0.01)       (the 0.01 keeps black pixels finite)
///      squared   mean_c d_c²
///      signed    mean_c d_c / (|ref_c| + 0.01)        (above the reference > 0, below < 0: bias)
///      relmse    mean_c d_c² / (ref_c² + 0.01)        (tev's relative squared error)
///      smape     mean_c |d_c| / (|pred_c| + |ref_c| + 0.01)   (symmetric; in [0, 1])
///  - Statistics over a set of pixels (a mask), every channel of every pixel one entry:
///      RMSE = sqrt(mean d²), relative RMSE = sqrt(mean (d / (|ref| + 0.01))²), MAE = mean |d|,
///      max = max |d|, plus the pixel count and the mean reference value (for scale);
///      signed relative mean = mean d / (|ref| + 0.01) (the bias: a 2 % low prediction gives −0.02,
///      which the RMSE, its spread, does not show), relMSE = mean d² / (ref² + 0.01) and
///      SMAPE = mean |d| / (|pred| + |ref| + 0.01), so figures compare with the literature's.
///  - The reference's own noise. A reference r is a Monte Carlo mean: for a prediction p and the
///    truth t, E[(p − r)²] = (p − t)² + Var(r). Given the reference's per-pixel variance of the mean
///    v = Var(r) (the renderer's, per channel), RMSE and relative RMSE come with
///      noise floor   sqrt(mean v)                  and  sqrt(mean v / (|ref| + 0.01)²)
///                    (the figure the reference's noise alone gives: a perfect prediction's expected error)
///      corrected     sqrt(max(0, mean(d² − v)))    and  sqrt(max(0, mean((d² − v) / (|ref| + 0.01)²)))
///                    (an unbiased estimate of the squared error against the truth, clamped at 0)
///    over the same pixels, and for relMSE  noise floor mean v / (ref² + 0.01), corrected
///    max(0, mean (d² − v) / (ref² + 0.01)) (a mean of squares, no root, as tev reports it; its
///    weight uses the noisy reference too, which correlates with d: off by about 4σ²/e relative,
///    for a relative error e of either sign and relative noise σ, where ε ≪ ref²). The signed mean is not corrected: it reads about σ²
///    high (E[1/r] = (1 + σ²)/t), negligible for a converged reference. SMAPE has no correction
///    (it is not a mean of squares) and reads high by the reference's noise. The absolute figure is unbiased. The relative one is so to first order in
///    the reference's relative noise σ/(|ref| + 0.01): its weight uses the noisy reference, which
///    leaves a bias of order (σ/(|ref| + 0.01))² times the figure (tests/test_noise_floor.cpp derives
///    it), so it needs a reference whose per-pixel relative noise is small.
///    Without the variance (a reference saved without it) both are unknown:
///    NaN, "unknown" in tables and null in JSON, never 0. MAE and max stay raw.
///  - A pixel whose prediction or reference has a NaN/Inf channel is left out of the statistics and
///    counted (`nonFinite`); in the maps it is NaN, which falseColor() shows as magenta and
///    floatMap() turns into 0 with the count reported. Nothing non-finite is ever averaged in.
/// All sums are in double and run in pixel order, so results are deterministic.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/image.h"
#include "core/util/relative_error.h"

namespace rrf {

// kRelativeEpsilon, the denominator offset of the relative error, is defined once in
// core/util/relative_error.h (the trainers and the data generator use it too).

enum class ErrorMapKind { Absolute, Relative, Squared, Signed, RelativeSquared, Smape };
/// Every kind, in the order the workbench offers them.
constexpr ErrorMapKind kErrorMapKinds[] = {ErrorMapKind::Absolute, ErrorMapKind::Relative,        ErrorMapKind::Squared,
                                           ErrorMapKind::Signed,   ErrorMapKind::RelativeSquared, ErrorMapKind::Smape};
/// True for the kind whose values have a sign (Signed): shown on a diverging map centred at 0
/// (signedFalseColor) over ±its scale, the others on viridis over [0, scale].
bool errorMapIsSigned(ErrorMapKind k);
/// "absolute" | "relative" | "squared" | "signed" | "relmse" | "smape": the spelling of reports, file
/// names and scripts.
const char* errorMapName(ErrorMapKind k);
/// The kind spelled `name` (as errorMapName writes it); nullopt for anything else, so each front end
/// names the bad value in its own terms.
std::optional<ErrorMapKind> parseErrorMapKind(std::string_view name);
/// The per-pixel formula for labels, e.g. "mean_c |d_c| / (|ref_c| + 0.01)".
const char* errorMapFormula(ErrorMapKind k);

struct ErrorStats {
    uint64_t pixels = 0;     ///< pixels in the mask with finite prediction, reference (and variance)
    uint64_t nonFinite = 0;  ///< pixels in the mask left out because of NaN/Inf (or a negative variance)
    double rmse = 0, relativeRmse = 0, mae = 0, maxError = 0;
    double meanReference = 0;  ///< mean reference value (all channels), to put the RMSE in scale
    double signedRelativeMean = 0;  ///< mean d / (|ref| + 0.01): the bias (> 0 above the reference)
    double relMse = 0;              ///< mean d² / (ref² + 0.01)
    double smape = 0;               ///< mean |d| / (|pred| + |ref| + 0.01)
    /// True when the reference's variance was given: the four figures below are then numbers,
    /// otherwise NaN ("unknown"). See the header comment for the formulas.
    bool noiseKnown = false;
    double rmseNoiseFloor = kUnknownNoise, rmseCorrected = kUnknownNoise;
    double relativeRmseNoiseFloor = kUnknownNoise, relativeRmseCorrected = kUnknownNoise;
    double relMseNoiseFloor = kUnknownNoise, relMseCorrected = kUnknownNoise;

    static constexpr double kUnknownNoise = std::numeric_limits<double>::quiet_NaN();
};

/// Statistics over the pixels listed in `mask` (indices y·width + x). Throws std::invalid_argument if
/// the image sizes differ or an index is out of range. An empty mask gives pixels = 0 and zeros.
/// The noise floor and corrected figures are unknown (the reference's variance is not given).
ErrorStats errorStats(const Image& prediction, const Image& reference, const std::vector<uint32_t>& mask);
/// Statistics over every pixel (noise unknown).
ErrorStats errorStats(const Image& prediction, const Image& reference);
/// As above, with the reference's per-pixel, per-channel variance of the mean `referenceVariance`
/// (same size as the reference): the noise floor and noise-corrected figures are filled in. An empty
/// `referenceVariance` means "not known" (as the overloads without it). A pixel with a non-finite or
/// negative variance is left out and counted like a non-finite one.
/// (A name of its own: errorStats(p, r, {}) stays the empty mask.)
ErrorStats errorStatsWithNoise(const Image& prediction, const Image& reference, const Image& referenceVariance,
                               const std::vector<uint32_t>& mask);
/// Statistics over every pixel, with the reference's variance of the mean (see above).
ErrorStats errorStatsWithNoise(const Image& prediction, const Image& reference, const Image& referenceVariance);

/// A noise figure for tables: the number as printf "%.4g" writes it, or "unknown" for NaN (a
/// reference without its variance) — an unknown floor is never shown as 0.
std::string noiseFigureText(double value);

/// Error of one pixel as the maps define it (the mean over R, G, B of the kind's per-channel term);
/// NaN where a channel of either input is non-finite. errorMap() is this function at every pixel, so a
/// read-out of one pixel shows exactly the map's value.
float pixelError(const Vec3& prediction, const Vec3& reference, ErrorMapKind kind);

/// Per-pixel error map (one scalar per pixel in all three channels; NaN where an input is non-finite).
/// Throws std::invalid_argument if the image sizes differ.
Image errorMap(const Image& prediction, const Image& reference, ErrorMapKind kind);

/// Pixel masks from an object-id buffer (-1 = not an object): index = object id, ascending pixels.
/// Ids ≥ objectCount are ignored.
std::vector<std::vector<uint32_t>> objectMasks(const std::vector<int32_t>& objectIds, size_t objectCount);

/// The q-quantile (q ∈ [0,1], nearest rank) of the finite first-channel values of `scalar`; 0 when
/// there are none. Used for the false-colour range [0, p99].
float percentile(const Image& scalar, double q);

/// The false-colour scale of an error map of kind `k`: its 99th percentile, of |value| for a signed
/// map (shown over ±scale), so a few edge pixels do not wash out the rest.
float errorMapScale(const Image& map, ErrorMapKind k);

/// An error map in false colour at scale `scale`: viridis over [0, scale], or for a signed map the
/// cool-warm diverging map over [−scale, scale] (core/util/image.h). A scale ≤ 0 is taken as 1e-12.
Image errorMapColour(const Image& map, ErrorMapKind k, float scale);

/// Copy of `map` with non-finite pixels set to 0; their count goes to `replaced`. For EXR output.
Image finiteMap(const Image& map, uint64_t& replaced);

}  // namespace rrf
