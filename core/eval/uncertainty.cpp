#include "core/eval/uncertainty.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/eval/error_metrics.h"
#include "core/predict/predictor.h"

namespace rrf {

namespace {

/// Ranks 1…n of `v`, ties sharing the mean of the ranks they span.
std::vector<double> ranks(const std::vector<double>& v) {
    std::vector<size_t> order(v.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
    std::vector<double> r(v.size());
    for (size_t i = 0; i < order.size();) {
        size_t j = i;
        while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
        const double mean = 0.5 * double(i + j) + 1.0;
        for (size_t k = i; k <= j; ++k) r[order[k]] = mean;
        i = j + 1;
    }
    return r;
}

}  // namespace

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size())
        throw std::invalid_argument("spearman: " + std::to_string(a.size()) + " and " + std::to_string(b.size()) + " values");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (a.size() < 2) return nan;
    const std::vector<double> ra = ranks(a), rb = ranks(b);
    const double mean = 0.5 * double(a.size() + 1);  // the mean of ranks 1…n, ties included
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double da = ra[i] - mean, db = rb[i] - mean;
        sab += da * db;
        saa += da * da;
        sbb += db * db;
    }
    if (saa == 0 || sbb == 0) return nan;
    return sab / std::sqrt(saa * sbb);
}

Image relativeSpreadMap(const Image& spread, const Image& prediction, const std::vector<uint8_t>& known) {
    if (spread.width != prediction.width || spread.height != prediction.height)
        throw std::invalid_argument("relativeSpreadMap: the spread's size is not the prediction's");
    if (!known.empty() && known.size() != size_t(spread.width) * size_t(spread.height))
        throw std::invalid_argument("relativeSpreadMap: the known-pixel mask's size is not the image's");
    Image out(spread.width, spread.height);
    for (int y = 0; y < spread.height; ++y)
        for (int x = 0; x < spread.width; ++x) {
            const size_t i = size_t(y) * size_t(spread.width) + size_t(x);
            if (!known.empty() && !known[i]) continue;
            const Vec3 s = spread.at(x, y), p = prediction.at(x, y);
            float v = 0.f;
            for (int c = 0; c < 3; ++c) v += s[c] / (std::abs(p[c]) + float(kRelativeEpsilon));
            v /= 3.f;
            out.set(x, y, Vec3(v));
        }
    return out;
}

float relativeSpreadScale(const Image& rel, const std::vector<uint8_t>& known) {
    // percentile() leaves non-finite values out: unknown pixels become NaN in a copy.
    Image knownOnly = rel;
    if (!known.empty())
        for (size_t i = 0; i < knownOnly.pixelCount(); ++i)
            if (i >= known.size() || !known[i]) knownOnly.data[3 * i] = std::numeric_limits<float>::quiet_NaN();
    return std::max(percentile(knownOnly, 0.99), 1e-6f);
}

UncertaintyEvaluation evaluateUncertainty(const Prediction& prediction, const Image& reference,
                                          const std::vector<std::vector<uint32_t>>& masks,
                                          const std::vector<uint32_t>& covered) {
    UncertaintyEvaluation u;
    if (prediction.spread.empty()) return u;
    u.available = true;
    const Image& pred = prediction.image(Term::Global);
    const Image rel = relativeSpreadMap(prediction.spread, pred, prediction.spreadKnown);
    auto stats = [&](const std::vector<uint32_t>& px) {
        std::vector<double> s, e;
        for (uint32_t i : px) {
            // An empty mask: every pixel's spread is known (as relativeSpreadMap reads it).
            if (!prediction.spreadKnown.empty() && (i >= prediction.spreadKnown.size() || !prediction.spreadKnown[i])) continue;
            if (i >= size_t(pred.width) * size_t(pred.height)) continue;
            const int x = int(i % uint32_t(pred.width)), y = int(i / uint32_t(pred.width));
            const double sv = rel.at(x, y).x;
            const double ev = pixelError(pred.at(x, y), reference.at(x, y), ErrorMapKind::Relative);
            if (!std::isfinite(sv) || !std::isfinite(ev)) continue;
            s.push_back(sv);
            e.push_back(ev);
        }
        UncertaintyStats st;
        st.pixels = s.size();
        if (!s.empty()) {
            st.meanRelativeSpread = std::accumulate(s.begin(), s.end(), 0.0) / double(s.size());
            st.meanRelativeError = std::accumulate(e.begin(), e.end(), 0.0) / double(e.size());
        }
        st.spearman = spearman(s, e);
        return st;
    };
    for (const std::vector<uint32_t>& px : masks) u.perObject.push_back(stats(px));
    u.overall = stats(covered);
    return u;
}

}  // namespace rrf
