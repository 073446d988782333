#include "core/eval/held_out.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/util/rng.h"

namespace rrf {

std::vector<Vec3> heldOutLightPositions(const Bounds3& region, int k, uint64_t seed) {
    std::vector<Vec3> out;
    if (k <= 0) return out;
    // "HELDOUT!" keys a stream of its own: the generator's records use mix64(seed ^ "RECORDS!").
    const uint64_t s = mix64(seed ^ 0x48454C444F555421ULL);
    const Vec3 lo = region.lo, ext = region.empty() ? Vec3(0.f) : region.extent();
    for (int i = 0; i < k; ++i) {
        Rng rng(s, uint64_t(i));
        const float u = rng.uniform(), v = rng.uniform(), w = rng.uniform();
        out.push_back(Vec3(lo.x + ext.x * u, lo.y + ext.y * v, lo.z + ext.z * w));
    }
    return out;
}

void Spread::add(double v) {
    if (count == 0) {
        mean = min = max = v;
    } else {
        mean += (v - mean) / double(count + 1);
        min = std::min(min, v);
        max = std::max(max, v);
    }
    ++count;
}

void HeldOutSummary::Row::add(const ErrorStats& s) {
    rmse.add(s.rmse);
    relativeRmse.add(s.relativeRmse);
    if (!s.noiseKnown) return;  // an unknown floor is left out of the spread, never counted as 0
    rmseNoiseFloor.add(s.rmseNoiseFloor);
    rmseCorrected.add(s.rmseCorrected);
    relativeRmseNoiseFloor.add(s.relativeRmseNoiseFloor);
    relativeRmseCorrected.add(s.relativeRmseCorrected);
}

HeldOutSummary summarizeHeldOut(const std::vector<Evaluation>& evaluations, size_t objectCount) {
    HeldOutSummary s;
    for (int t = 0; t < kTermCount; ++t) s.perObject[t].resize(objectCount);
    for (const Evaluation& e : evaluations)
        for (int t = 0; t < kTermCount; ++t) {
            const TermErrors& te = e.terms[t];
            s.available[t] = s.available[t] && te.available;
            for (size_t id = 0; id < std::min(objectCount, te.perObject.size()); ++id) {
                if (te.perObject[id].pixels) s.perObject[t][id].add(te.perObject[id]);
            }
            if (te.overall.pixels) s.overall[t].add(te.overall);
        }
    for (const Evaluation& e : evaluations) {
        if (!e.flip.available || !e.flip.hdr.pixels) continue;
        s.flipHdr.add(e.flip.hdr.mean);
        s.flipLdr.add(e.flip.ldr.mean);
        if (std::isfinite(e.flip.hdrNoiseFloor)) s.flipHdrNoiseFloor.add(e.flip.hdrNoiseFloor);
    }
    s.spearmanPerObject.resize(objectCount);
    for (const Evaluation& e : evaluations) {
        if (!e.uncertainty.available) continue;
        if (std::isfinite(e.uncertainty.overall.spearman)) s.spearman.add(e.uncertainty.overall.spearman);
        for (size_t id = 0; id < e.uncertainty.perObject.size() && id < objectCount; ++id)
            if (std::isfinite(e.uncertainty.perObject[id].spearman)) s.spearmanPerObject[id].add(e.uncertainty.perObject[id].spearman);
    }
    return s;
}

std::string heldOutTable(const Scene& scene, const HeldOutSummary& s) {
    std::ostringstream out;
    char line[400];
    std::snprintf(line, sizeof line, "%-9s %-14s %3s | %-29s | %11s | %-29s | %-29s | %11s | %10s\n", "term", "object", "K",
                  "rel.RMSE mean/min/max", "noise floor", "corrected mean/min/max", "RMSE mean/min/max", "noise floor",
                  "corrected");
    out << line;
    for (int t = 0; t < kTermCount; ++t) {
        if (!s.available[t]) {
            std::snprintf(line, sizeof line, "%-9s (not predicted by these networks)\n", termName(Term(t)));
            out << line;
            continue;
        }
        auto row = [&](const std::string& name, const HeldOutSummary::Row& r) {
            // Corrected min/max exist only where the noise was known; "unknown" otherwise.
            const Spread& c = r.relativeRmseCorrected;
            const std::string cMin = noiseFigureText(c.count ? c.min : ErrorStats::kUnknownNoise);
            const std::string cMax = noiseFigureText(c.count ? c.max : ErrorStats::kUnknownNoise);
            std::snprintf(line, sizeof line,
                          "%-9s %-14s %3d | %9.4g %9.4g %9.4g | %11s | %9s %9s %9s | %9.4g %9.4g %9.4g | %11s | %10s\n",
                          termName(Term(t)), name.substr(0, 14).c_str(), r.rmse.count, r.relativeRmse.mean, r.relativeRmse.min,
                          r.relativeRmse.max, noiseFigureText(r.relativeRmseNoiseFloor.meanOrUnknown()).c_str(),
                          noiseFigureText(c.meanOrUnknown()).c_str(), cMin.c_str(), cMax.c_str(), r.rmse.mean, r.rmse.min,
                          r.rmse.max, noiseFigureText(r.rmseNoiseFloor.meanOrUnknown()).c_str(),
                          noiseFigureText(r.rmseCorrected.meanOrUnknown()).c_str());
            out << line;
        };
        for (size_t id = 0; id < s.perObject[t].size(); ++id)
            if (s.perObject[t][id].rmse.count) row(id < scene.objects.size() ? scene.objects[id].name : std::to_string(id), s.perObject[t][id]);
        row("ALL OBJECTS", s.overall[t]);
    }
    out << "noise floor: the error the references' own noise gives (mean over the K lights); corrected: the error "
           "with that noise subtracted, an estimate against the noise-free truth\n";
    if (s.flipHdr.count) {
        std::snprintf(line, sizeof line,
                      "FLIP (global, all objects, %d lights): HDR-FLIP mean %.4g (min %.4g, max %.4g), noise floor %s; "
                      "LDR-FLIP mean %.4g\n",
                      s.flipHdr.count, s.flipHdr.mean, s.flipHdr.min, s.flipHdr.max,
                      noiseFigureText(s.flipHdrNoiseFloor.meanOrUnknown()).c_str(), s.flipLdr.mean);
        out << line;
    }
    if (s.spearman.count) {
        std::snprintf(line, sizeof line,
                      "uncertainty (ensemble spread against the true error, %d lights): Spearman mean %.3f (min %.3f, max %.3f)\n",
                      s.spearman.count, s.spearman.mean, s.spearman.min, s.spearman.max);
        out << line;
        for (size_t id = 0; id < s.spearmanPerObject.size(); ++id) {
            const Spread& o = s.spearmanPerObject[id];
            if (!o.count) continue;
            std::snprintf(line, sizeof line, "  %-14s Spearman mean %.3f (min %.3f, max %.3f)\n",
                          (id < scene.objects.size() ? scene.objects[id].name : std::to_string(id)).substr(0, 14).c_str(),
                          o.mean, o.min, o.max);
            out << line;
        }
    }
    return out.str();
}

}  // namespace rrf
