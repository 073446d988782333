#pragma once
/// FLIP, NVIDIA's perceptual image difference evaluator, written from its papers:
///  - LDR-FLIP: Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG 2020
///    (colour pipeline, feature pipeline, final error).
///  - HDR-FLIP: Andersson et al., "Visualizing Errors in Rendered High Dynamic Range Images",
///    Eurographics 2021 short paper (exposure range, tone mapping, max over exposures).
///  - Pooling and colour map: Andersson et al., "Visualizing and Communicating Errors in Rendered
///    Images", Ray Tracing Gems II, 2021 (weighted median and quartiles, magma error maps).
///
/// Conventions (chosen once for this project):
///  - Inputs are this project's images: LINEAR RGB radiance (Rec. 709 / sRGB primaries). The
///    paper's LDR-FLIP takes sRGB-encoded images and decodes them to linear RGB as its first step;
///    ldrFlip() starts after that step: it clamps each linear channel to [0, 1] and converts to XYZ
///    directly, so an sRGB image must be decoded (srgbToLinear) before it is passed in.
///  - Outputs are per-pixel maps with one scalar in [0, 1] stored in all three channels.
///  - Boundaries: every filter clamps to the edge (the border pixel is repeated), as the authors'
///    tools do, so a uniform image stays uniform after filtering, borders included.
///  - A pixel with a NaN or infinite channel in either input is NaN in every map (flipColour()
///    shows it magenta); for filtering it counts as black, so its neighbours still get an error.
///    Statistics leave such pixels out and count them (`nonFinite`), as core/eval/error_metrics.h.
///  - Deterministic: every filter sums its taps in a fixed order, statistics sum in double.

#include <cstdint>
#include <vector>

#include "core/util/image.h"
#include "core/util/vec3.h"

namespace rrf {

/// Pixels per degree of visual angle for the papers' default observer: 0.7 m from a 0.7 m wide
/// monitor with 3840 pixels across, ppd = distance · (pixels / width) · π / 180 ≈ 67.02 (HPG 2020,
/// "the number of pixels per degree"). The one source of the default.
inline constexpr double kFlipDefaultPixelsPerDegree = 0.7 * (3840.0 / 0.7) * (3.14159265358979323846 / 180.0);

/// Viewing conditions. The filters' widths scale with pixelsPerDegree: a larger value (a farther
/// observer or a denser display) hides finer detail. Must be finite and > 0.
struct FlipSettings {
    double pixelsPerDegree = kFlipDefaultPixelsPerDegree;
};

/// LDR-FLIP (HPG 2020): ΔE = ΔEc^(1 − ΔEf) per pixel, in [0, 1], 0 for identical inputs.
/// Linear RGB inputs, each channel clamped to [0, 1]. Throws std::invalid_argument if the sizes
/// differ or the settings are invalid; empty inputs give an empty map.
Image ldrFlip(const Image& reference, const Image& test, const FlipSettings& settings = {});

/// The colour term ΔEc alone (HPG 2020, colour pipeline): YCxCz, contrast-sensitivity filtering,
/// back to linear RGB clamped to [0, 1], Hunt-adjusted CIELAB, HyAB distance, the 0.7 power and
/// the compression to [0, 1] relative to the green–blue distance. In [0, 1]; for diagnostics
/// (which part of ldrFlip() an error comes from) and for tests. Same inputs and errors as ldrFlip().
Image flipColourDifference(const Image& reference, const Image& test, const FlipSettings& settings = {});

/// The feature term ΔEf alone (HPG 2020, feature pipeline): the larger of the edge-strength and
/// point-strength differences of the luminance, ((1/√2) · max)^0.5, in [0, 1]. Same inputs and
/// errors as ldrFlip().
Image flipFeatureDifference(const Image& reference, const Image& test, const FlipSettings& settings = {});

/// The exposures HDR-FLIP evaluates (EG 2021): `count` exposures (stops, the image is scaled by
/// 2^exposure) evenly spaced from start to stop, both included (count 1: start only).
struct FlipExposureRange {
    double start = 0.0;
    double stop = 0.0;
    int count = 2;
};

/// The i-th exposure of `range` (0 ≤ i < count): start + i · (stop − start) / max(count − 1, 1).
double flipExposure(const FlipExposureRange& range, int i);

/// HDR-FLIP's automatic exposure range from the REFERENCE alone (EG 2021), so error figures of
/// different test images against one reference use the same exposures and compare:
///   x85   the tone mapper input that flipToneMap() maps to 0.85,
///   start = log2(x85 / Ymax)      (the brightest pixel just below white),
///   stop  = log2(x85 / Ymedian)   (the median pixel, as bright),
///   count = max(2, ceil(stop − start)),
/// with Y = Rec. 709 luminance of max(rgb, 0). The median is the 50th percentile with linear
/// interpolation (for an even count, the mean of the middle two). Non-finite pixels are ignored.
/// Choices where the paper is silent: an all-black reference gives start = stop = 0; if the median
/// is 0 (mostly black images), the median of the positive luminances is used instead, so the range
/// stays finite and still reaches the lit part of the image.
FlipExposureRange flipExposureRange(const Image& reference);

/// HDR-FLIP's display model for one exposure (EG 2021): per channel, x = 2^exposure · max(v, 0),
/// then Narkowicz's ACES fit applied to 0.6 · x, (0.6x(2.51 · 0.6x + 0.03)) /
/// (0.6x(2.43 · 0.6x + 0.59) + 0.14), clamped to [0, 1]. The result is linear RGB, ready for
/// ldrFlip(). Non-finite values become NaN.
Image flipToneMap(const Image& hdr, double exposure);

/// HDR-FLIP (EG 2021): for every exposure of `range`, tone map both images with flipToneMap() and
/// run ldrFlip(); the error is the per-pixel maximum over exposures, in [0, 1]. Symmetric in
/// reference and test for a fixed range; take the range from flipExposureRange(reference).
/// If `maxExposureIndex` is given it receives, per pixel (y · width + x), the index of the first
/// exposure that reached the maximum (−1 where the error is NaN): the paper's exposure map.
/// Throws std::invalid_argument for differing sizes, invalid settings, count < 1 or a
/// non-finite start or stop.
Image hdrFlip(const Image& reference, const Image& test, const FlipExposureRange& range,
              const FlipSettings& settings = {}, std::vector<int>* maxExposureIndex = nullptr);

/// Pooled values of a FLIP map (first channel), as the FLIP tools print them (RTG II 2021).
/// The weighted percentiles weight every pixel by its own error, which is what the weighted FLIP
/// histogram shows: the weighted median is the error at which half of the total error sum lies
/// below. Definition (the authors' Python tool): sort the errors ascending, find the first index k
/// whose cumulative sum reaches p · (sum of all errors), and take the mean of the k-th and
/// (k+1)-th sorted errors (the k-th alone when it is the last). An all-zero map gives 0.
struct FlipStats {
    double mean = 0.0;
    double weightedMedian = 0.0;
    double weightedFirstQuartile = 0.0;  ///< p = 0.25
    double weightedThirdQuartile = 0.0;  ///< p = 0.75
    double min = 0.0;
    double max = 0.0;
    uint64_t pixels = 0;     ///< finite pixels the figures are over
    uint64_t nonFinite = 0;  ///< pixels left out because their error is NaN or infinite
};

/// FlipStats over every pixel. All figures are 0 when no finite pixel remains.
FlipStats flipStats(const Image& flipMap);
/// FlipStats over the pixels y · width + x listed in `pixels` (a mask; a pixel listed twice counts
/// twice). Throws std::out_of_range for an index ≥ width · height.
FlipStats flipStats(const Image& flipMap, const std::vector<uint32_t>& pixels);

/// The magma colour (linear RGB) for t in [0, 1] (clamped, NaN gives the bottom), the map the FLIP
/// tools colour their error maps with. Like viridis() in core/util/image.h: matplotlib's sRGB table
/// (van der Walt & Smith, CC0), decoded to linear so a PNG written with exposure 0 shows the
/// published colours.
Vec3 magma(float t);

/// A FLIP map (first channel) in magma over [0, 1]; non-finite errors become magenta (1, 0, 1),
/// which magma never produces, as falseColor() does.
Image flipColour(const Image& flipMap);

}  // namespace rrf
