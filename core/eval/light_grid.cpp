#include "core/eval/light_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/data/dataset_file.h"
#include "core/util/error.h"

namespace rrf {

namespace {
constexpr int kMaxGridCount = 64;
constexpr size_t kMaxGridPoints = 4096;
const double kNoFigure = std::numeric_limits<double>::quiet_NaN();

float axisOf(const Vec3& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }

/// Grid coordinate `i` of `n` along [lo, hi]: the ends included, the centre for a single point.
float gridCoordinate(float lo, float hi, int i, int n) {
    return n > 1 ? lo + (hi - lo) * float(i) / float(n - 1) : 0.5f * (lo + hi);
}

/// The figure a map shows: noise-corrected where the reference's noise was known, else raw.
double shownFigure(const ErrorStats& s) {
    if (s.pixels == 0) return kNoFigure;
    return std::isfinite(s.relativeRmseCorrected) ? s.relativeRmseCorrected : s.relativeRmse;
}

std::string gridFigureText(double v) {
    if (!std::isfinite(v)) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4f", v);
    return buf;
}
}  // namespace

LightGridSpec LightGridSpec::parse(const std::string& text, const std::string& source, const std::string& field) {
    LightGridSpec g;
    const std::string expected = "NxMxK, three whole numbers from 1 to " + std::to_string(kMaxGridCount) +
                                 " (light positions along x, y and z of the light region), e.g. 4x2x4; got '" + text + "'";
    size_t at = 0;
    for (int a = 0; a < 3; ++a) {
        if (a > 0) {
            if (at >= text.size() || (text[at] != 'x' && text[at] != 'X')) throw InputError(source, field, expected);
            ++at;
        }
        size_t digits = 0;
        long value = 0;
        while (at < text.size() && text[at] >= '0' && text[at] <= '9' && digits < 4) {
            value = value * 10 + (text[at] - '0');
            ++at;
            ++digits;
        }
        if (digits == 0 || value < 1 || value > kMaxGridCount) throw InputError(source, field, expected);
        g.counts[a] = int(value);
    }
    if (at != text.size()) throw InputError(source, field, expected);
    if (g.size() > kMaxGridPoints)
        throw InputError(source, field,
                         "at most " + std::to_string(kMaxGridPoints) + " light positions (each needs its own reference); got " +
                             std::to_string(g.size()) + " from '" + text + "'");
    return g;
}

std::vector<Vec3> LightGridSpec::positions(const Bounds3& region) const {
    std::vector<Vec3> out(size());
    for (int j = 0; j < counts[1]; ++j)
        for (int k = 0; k < counts[2]; ++k)
            for (int i = 0; i < counts[0]; ++i)
                out[index(i, j, k)] = Vec3(gridCoordinate(region.lo.x, region.hi.x, i, counts[0]),
                                           gridCoordinate(region.lo.y, region.hi.y, j, counts[1]),
                                           gridCoordinate(region.lo.z, region.hi.z, k, counts[2]));
    return out;
}

std::string LightGridSpec::text() const {
    return std::to_string(counts[0]) + "x" + std::to_string(counts[1]) + "x" + std::to_string(counts[2]);
}

void checkLightGrid(const LightGridSpec& grid, const Scene& scene, const std::string& source, const std::string& field) {
    if (scene.lightRegion.empty())
        throw InputError(source, field, "the scene's light does not move (it has no \"light_region\"): there is no region to span");
    const char* axes[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a)
        if (grid.counts[a] > 1 && !(axisOf(scene.lightRegion.hi, a) > axisOf(scene.lightRegion.lo, a))) {
            char why[200];
            std::snprintf(why, sizeof why,
                          "the light region is flat along %s (%g to %g): give one point along it instead of %d", axes[a],
                          double(axisOf(scene.lightRegion.lo, a)), double(axisOf(scene.lightRegion.hi, a)), grid.counts[a]);
            throw InputError(source, field, why);
        }
}

double LightGridMap::scaleOf(const std::vector<double>& values) {
    double s = 0.0;
    for (double v : values)
        if (std::isfinite(v)) s = std::max(s, v);
    return s;
}

bool LightGridMap::inSlice(const Vec3& p, int j) const {
    const int ny = grid.counts[1];
    if (ny <= 1) return true;
    const float y0 = region.lo.y, y1 = region.hi.y;
    return std::fabs(p.y - gridCoordinate(y0, y1, j, ny)) <= 0.5f * (y1 - y0) / float(ny - 1);
}

float LightGridMap::cellCoordinate(const Vec3& p, int a) const {
    const int n = grid.counts[a];
    const float lo = axisOf(region.lo, a), hi = axisOf(region.hi, a);
    return (n > 1 && hi > lo ? (axisOf(p, a) - lo) / (hi - lo) * float(n - 1) : 0.f) + 0.5f;
}

LightGridMap lightGridMap(const LightGridSpec& grid, const Bounds3& region, const std::vector<Evaluation>& evaluations,
                          size_t objectCount) {
    if (evaluations.size() != grid.size())
        throw std::invalid_argument("lightGridMap: " + std::to_string(evaluations.size()) + " evaluations for a " +
                                    grid.text() + " grid");
    LightGridMap m;
    m.grid = grid;
    m.region = region;
    m.objects.assign(objectCount, std::vector<double>(grid.size(), kNoFigure));
    for (size_t n = 0; n < evaluations.size(); ++n) {
        const Evaluation& e = evaluations[n];
        const TermErrors& g = e.term(Term::Global);
        m.lights.push_back(e.lightPosition);
        m.global.push_back(shownFigure(g.overall));
        m.globalRaw.push_back(g.overall.pixels ? g.overall.relativeRmse : kNoFigure);
        m.globalNoiseFloor.push_back(g.overall.relativeRmseNoiseFloor);
        for (size_t id = 0; id < objectCount && id < g.perObject.size(); ++id) m.objects[id][n] = shownFigure(g.perObject[id]);
    }
    return m;
}

std::vector<Vec3> datasetLightPositions(const Dataset& dataset, size_t maxCount) {
    const std::vector<std::string>& layout = dataset.inputLayout();
    int column[3] = {-1, -1, -1};
    const char* names[3] = {"light_x", "light_y", "light_z"};
    for (int a = 0; a < 3; ++a) {
        const auto it = std::find(layout.begin(), layout.end(), names[a]);
        if (it == layout.end())
            throw InputError(dataset.path(), "/input_layout", std::string("no \"") + names[a] + "\" input: the records carry no light position");
        column[a] = int(it - layout.begin());
    }
    std::vector<Vec3> out;
    const uint64_t total = dataset.totalRecords();
    if (total == 0 || maxCount == 0) return out;
    const int stride = dataset.floatsPerRecord();
    for (size_t o = 0; o < dataset.objects().size(); ++o) {
        const uint64_t count = dataset.objects()[o].count;
        // Each object gets its share of the marks, records picked evenly through its block.
        const uint64_t share = std::max<uint64_t>(1, uint64_t(double(maxCount) * double(count) / double(total)));
        const uint64_t step = std::max<uint64_t>(1, count / share);
        const float* r = dataset.records(o);
        for (uint64_t n = 0; n < count && out.size() < maxCount; n += step) {
            const float* rec = r + n * uint64_t(stride);
            out.emplace_back(rec[column[0]], rec[column[1]], rec[column[2]]);
        }
    }
    return out;
}

Image lightGridSlice(const LightGridMap& map, const std::vector<double>& values, int j, int cell, double scale) {
    const int nx = map.grid.counts[0], ny = map.grid.counts[1], nz = map.grid.counts[2];
    if (j < 0 || j >= ny) throw std::invalid_argument("lightGridSlice: no slice " + std::to_string(j));
    if (values.size() != map.grid.size()) throw std::invalid_argument("lightGridSlice: one value per grid point expected");
    Image scalar(nx * cell, nz * cell);
    for (int k = 0; k < nz; ++k)
        for (int i = 0; i < nx; ++i) {
            const float v = float(values[map.grid.index(i, j, k)]);
            for (int y = 0; y < cell; ++y)
                for (int x = 0; x < cell; ++x) scalar.set(i * cell + x, k * cell + y, Vec3(v));
        }
    Image img = falseColor(scalar, 0.f, float(std::max(scale, 1e-12)));
    for (const Vec3& p : map.marks) {
        if (!map.inSlice(p, j)) continue;
        const int px = int(std::floor(map.cellCoordinate(p, 0) * float(cell)));
        const int py = int(std::floor(map.cellCoordinate(p, 2) * float(cell)));
        if (px >= 0 && px < img.width && py >= 0 && py < img.height) img.set(px, py, Vec3(1.f));
    }
    return img;
}

std::string lightGridTable(const Scene& scene, const LightGridMap& map) {
    std::string s;
    char line[160];
    const int nx = map.grid.counts[0], ny = map.grid.counts[1], nz = map.grid.counts[2];
    for (int j = 0; j < ny; ++j) {
        std::snprintf(line, sizeof line, "light y = %.3f (global relative RMSE; x across, z down)\n",
                      gridCoordinate(map.region.lo.y, map.region.hi.y, j, ny));
        s += line;
        s += "          z \\ x";
        for (int i = 0; i < nx; ++i) {
            std::snprintf(line, sizeof line, " %8.3f", gridCoordinate(map.region.lo.x, map.region.hi.x, i, nx));
            s += line;
        }
        s += "\n";
        for (int k = 0; k < nz; ++k) {
            std::snprintf(line, sizeof line, "%15.3f", gridCoordinate(map.region.lo.z, map.region.hi.z, k, nz));
            s += line;
            for (int i = 0; i < nx; ++i) {
                std::snprintf(line, sizeof line, " %8s", gridFigureText(map.global[map.grid.index(i, j, k)]).c_str());
                s += line;
            }
            s += "\n";
        }
    }
    s += "worst light position per object:\n";
    for (size_t id = 0; id < map.objects.size() && id < scene.objects.size(); ++id) {
        const std::vector<double>& v = map.objects[id];
        size_t worst = v.size();
        for (size_t n = 0; n < v.size(); ++n)
            if (std::isfinite(v[n]) && (worst == v.size() || v[n] > v[worst])) worst = n;
        if (worst == v.size()) {
            std::snprintf(line, sizeof line, "  %-20s not visible at any grid light\n", scene.objects[id].name.c_str());
        } else {
            const Vec3& l = map.lights[worst];
            std::snprintf(line, sizeof line, "  %-20s %s at (%.3f, %.3f, %.3f)\n", scene.objects[id].name.c_str(),
                          gridFigureText(v[worst]).c_str(), l.x, l.y, l.z);
        }
        s += line;
    }
    return s;
}

}  // namespace rrf
