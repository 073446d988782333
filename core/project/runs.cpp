#include "core/project/runs.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <stdexcept>

namespace rrf {

namespace {
std::string formatTime(const char* fmt) {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    localtime_r(&now, &tm);
    char buf[64];
    std::strftime(buf, sizeof buf, fmt, &tm);
    return buf;
}

}  // namespace

std::vector<LossPoint> aggregateLoss(const std::vector<LossCurve>& curves) {
    int last = -1;
    for (const LossCurve& c : curves)
        if (!c.points.empty()) last = std::max(last, c.points.back().epoch);
    std::vector<LossPoint> out;
    if (last < 0) return out;
    std::vector<size_t> at(curves.size(), 0);  // per curve: index of the point for the current epoch
    for (int e = 0; e <= last; ++e) {
        double train = 0, validation = 0, seconds = 0;
        int nTrain = 0, nValidation = 0;
        for (size_t i = 0; i < curves.size(); ++i) {
            const std::vector<LossPoint>& p = curves[i].points;
            if (p.empty() || p.front().epoch > e) continue;
            while (at[i] + 1 < p.size() && p[at[i] + 1].epoch <= e) ++at[i];
            const LossPoint& q = p[at[i]];
            if (std::isfinite(q.train)) train += q.train, ++nTrain;
            if (std::isfinite(q.validation)) validation += q.validation, ++nValidation;
            seconds = std::max(seconds, q.seconds);
        }
        if (nTrain == 0 && nValidation == 0) continue;
        out.push_back({e, nTrain ? train / nTrain : std::numeric_limits<double>::quiet_NaN(), nValidation ? validation / nValidation : std::numeric_limits<double>::quiet_NaN(), seconds});
    }
    return out;
}

std::string newRunId(const std::vector<Run>& runs, const std::string& kind) {
    const std::string base = kind + "-" + formatTime("%Y%m%d-%H%M%S");
    auto used = [&](const std::string& id) {
        for (const Run& r : runs)
            if (r.id == id) return true;
        return false;
    };
    std::string id = base;
    for (int n = 2; used(id); ++n) id = base + "-" + std::to_string(n);
    return id;
}

std::string localTimestamp() { return formatTime("%Y-%m-%dT%H:%M:%S"); }

}  // namespace rrf
