#pragma once
/// Error across the light region (`rrf evaluate --light-grid NxMxK`, docs/design.md §14c): a model
/// judged at a regular grid of light positions spanning the whole region, edges included, so that a
/// user sees where in the region it fails (near the edges, where training records thin out; between
/// dense and sparse draws) rather than one average over a few random held-out lights. The figures
/// are laid out as slices of constant height (y): one x-by-z map per y of the grid, every slice on
/// one colour scale, with the training records' light positions of that height band marked.
/// core/eval/light_grid_json.h writes the figures.

#include <string>
#include <vector>

#include "core/eval/evaluation.h"
#include "core/scene/scene.h"
#include "core/util/image.h"

namespace rrf {

class Dataset;

/// N x M x K light positions along x, y and z of the light region.
struct LightGridSpec {
    int counts[3] = {1, 1, 1};

    /// Reads "NxMxK" (each 1..64, at most 4096 points). Throws InputError naming `source` and
    /// `field` (e.g. "command line", "--light-grid") and the expected form.
    static LightGridSpec parse(const std::string& text, const std::string& source, const std::string& field);
    size_t size() const { return size_t(counts[0]) * size_t(counts[1]) * size_t(counts[2]); }
    /// Index of grid point (i, j, k) along (x, y, z): x fastest, then z, then y, so that each slice of
    /// constant y is one contiguous block.
    size_t index(int i, int j, int k) const { return (size_t(j) * counts[2] + size_t(k)) * counts[0] + size_t(i); }
    /// The positions in index() order: min + (max - min) i / (n - 1) per axis, the centre where n is 1.
    std::vector<Vec3> positions(const Bounds3& region) const;
    std::string text() const;  ///< "NxMxK"
};

/// Refuses a grid `scene`'s light region cannot hold: no region (the light does not move), or more
/// than one point along an axis the region is flat in (every point there would be the same light).
/// Throws InputError naming `source` and `field`.
void checkLightGrid(const LightGridSpec& grid, const Scene& scene, const std::string& source, const std::string& field);

/// The judged figures of each grid point.
struct LightGridMap {
    LightGridSpec grid;
    Bounds3 region;
    std::vector<Vec3> lights;                  ///< in LightGridSpec::index() order
    /// Global term over all kept object pixels, per light: relative RMSE noise-corrected where the
    /// reference's noise is known, else raw (what the map shows), the raw figure and the noise floor.
    std::vector<double> global, globalRaw, globalNoiseFloor;
    /// The same figure (corrected where known) per object id and light; NaN where the object has no
    /// kept pixels at that light.
    std::vector<std::vector<double>> objects;
    /// The training records' light positions shown as marks (a sample of the dataset), and where
    /// they came from ("" when none are shown, `marksWhy` says why).
    std::vector<Vec3> marks;
    std::string marksSource, marksWhy;

    /// The largest finite figure of `values` (0 when none): the slices' shared colour scale.
    static double scaleOf(const std::vector<double>& values);
    /// Whether a mark at `p` belongs to slice `j`: its height is nearer to slice j's than to any
    /// other's (the band halfway to the neighbouring slices; every height for a single slice).
    bool inSlice(const Vec3& p, int j) const;
    /// Where `p` falls along axis `a` (0: x, 2: z) of a slice, in cells: grid point i sits at the
    /// centre of cell i, i + 0.5, and positions between points map linearly.
    float cellCoordinate(const Vec3& p, int a) const;
};

/// The map of `evaluations`, one per position of `grid` over `region` in index() order. Throws
/// std::invalid_argument when the counts differ.
LightGridMap lightGridMap(const LightGridSpec& grid, const Bounds3& region, const std::vector<Evaluation>& evaluations,
                          size_t objectCount);

/// Up to `maxCount` light positions of `dataset`'s records, spread evenly over each object's records
/// (its "light_x", "light_y", "light_z" inputs). Throws InputError naming the dataset when it has no
/// light inputs.
std::vector<Vec3> datasetLightPositions(const Dataset& dataset, size_t maxCount);

/// Slice `j` (constant y) of `values` (one per grid point) as a false-colour image: x to the right,
/// z downwards, each grid point a `cell` x `cell` square on viridis over [0, scale] (magenta: no
/// figure), and the marks whose y lies in the slice's height band as white dots at their (x, z).
Image lightGridSlice(const LightGridMap& map, const std::vector<double>& values, int j, int cell, double scale);

/// Per slice, a table of the global figure with x across and z down, then the worst light position
/// per object.
std::string lightGridTable(const Scene& scene, const LightGridMap& map);

}  // namespace rrf
