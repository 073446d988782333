#pragma once
/// The noise of a record's targets (docs/design.md §8, "Clean targets"): each target is the mean of
/// n path samples, and the generator stores the variance of that mean per channel (sample variance
/// / n). Its RELATIVE noise, on the scale of the relative error metric (ε = kRelativeEpsilon), is
///
///     r = max over the direct and the indirect term of  sqrt( mean_c v_c / (|m_c| + ε)² )
///
/// (m the mean, v the variance of the mean, c = R, G, B): the relative standard error of the worse
/// term, the figure the adaptive sampling drives below `noise_target` and `rrf inspect` and the
/// Sampling panel summarise per object (median and 90th percentile).

#include <cstddef>
#include <cstdint>
#include <limits>

namespace rrf {

/// Welford accumulator of the six target channels (direct RGB, indirect RGB) of one record's samples.
struct TargetAccumulator {
    int n = 0;
    double mean[6] = {}, m2[6] = {};

    void add(const double sample[6]) {
        ++n;
        for (int c = 0; c < 6; ++c) {
            const double d = sample[c] - mean[c];
            mean[c] += d / n;
            m2[c] += d * (sample[c] - mean[c]);
        }
    }
    /// Variance of the mean of channel c (sample variance / n); −1 with fewer than two samples.
    double varianceOfMean(int c) const { return n >= 2 ? m2[c] / double(n - 1) / double(n) : -1.0; }
};

/// r of the file comment from the six means and variances of the mean; NaN when a variance is
/// negative (unknown).
double relativeNoise(const float mean[6], const float varianceOfMean[6]);

/// Median and 90th percentile of r over a set of records; `known` counts the records whose noise is
/// known (the others are left out). Both figures are NaN when none is known.
struct NoiseSummary {
    uint64_t known = 0;
    double median = std::numeric_limits<double>::quiet_NaN();
    double p90 = std::numeric_limits<double>::quiet_NaN();
};

/// Summary over `count` records of `floatsPerRecord` floats whose targets start at `targetOffset` and
/// whose variances start at `noiseOffset` (the record layout's offsets).
NoiseSummary summarizeNoise(const float* records, size_t count, int floatsPerRecord, int targetOffset, int noiseOffset);

}  // namespace rrf
