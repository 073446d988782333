#pragma once
/// CPU G-buffer for network prediction (docs/design.md §13).
///
/// One primary ray through the CENTRE of every pixel (no jitter: a prediction is a function of the
/// pixel, not a Monte Carlo estimate) gives, per pixel, exactly the network input record of the data
/// generator (core/data/record_layout.h):
///
///     hit point (3), view direction (3), light position (3), normal (3), BRDF parameters (n)
///
/// with the view direction pointing FROM the hit point TO the eye and the geometric normal flipped to
/// the viewer's side, as DataGenerator::estimateRecord writes them. The light position is an input
/// column, so the G-buffer depends on it; it also decides which pixels see the movable light, which is
/// visible geometry. Emitter pixels carry their emitted radiance towards the eye (what the ground
/// truth's direct image shows there) and no network input.
///
/// The ground truth averages a box filter over each pixel, so a pixel whose footprint covers more than
/// one surface is a mixture the centre ray cannot reproduce. The per-pixel normal and distance below
/// exist for that test: core/predict/footprint_mask.h finds such pixels (another object, a crease, a
/// depth step or the light in the 3×3 neighbourhood), and every error statistic leaves them out and
/// counts them (docs/design.md §14).

#include <cstdint>
#include <vector>

#include "core/render/path_tracer.h"
#include "core/data/record_layout.h"

namespace rrf {

struct GBuffer {
    int width = 0, height = 0;
    int numInputs = 0;            ///< 12 + n (RecordLayout::inputCount())
    Vec3 lightPosition{0.f};      ///< centre of the movable light the buffer was made for
    /// numInputs floats per pixel, pixel i = y·width + x at [i·numInputs, (i+1)·numInputs); zero for
    /// pixels that hit no object. Column-major inputs × pixels, so it maps onto an Eigen matrix.
    std::vector<float> inputs;
    std::vector<int32_t> object;  ///< object id per pixel; -1 for background and emitter pixels
    std::vector<int32_t> light;   ///< light index for emitter pixels, -1 otherwise
    std::vector<Vec3> emitted;    ///< emitted radiance towards the eye (emitter pixels), else 0
    /// Unit geometric normal flipped to the viewer's side (the network input's normal) for object
    /// pixels, 0 elsewhere. The footprint mask compares neighbours' normals.
    std::vector<Vec3> normal;
    /// Distance from the eye to the hit point along the centre ray for object pixels, 0 elsewhere.
    /// The footprint mask measures depth steps relative to it.
    std::vector<float> distance;
    /// Unit geometric normal flipped to the viewer's side (object pixels; 0 elsewhere): where rays
    /// leaving the surface start and which side they leave on (the glossy gather).
    std::vector<Vec3> geometricNormal;
    /// Per pixel, or empty for none: exact direct light here leaves out the material's glossy lobe,
    /// because that light reaches the pixel's receiver as a caustic sampled from the light
    /// (core/predict/glossy_caustics.h). Only the glossy gather's secondary points set it.
    std::vector<uint8_t> directWithoutGloss;
    /// Pixel indices of every object (index = object id, ascending pixel order): the masks of the
    /// per-object error statistics and the batches of the predictor.
    std::vector<std::vector<uint32_t>> pixelsByObject;
    std::vector<uint32_t> emitterPixels;  ///< pixels that see an emitter, ascending
    uint64_t backgroundPixels = 0;        ///< pixels whose ray escapes

    size_t pixelCount() const { return size_t(width) * size_t(height); }
    const float* input(size_t pixel) const { return inputs.data() + pixel * size_t(numInputs); }
    /// Hit point of an object pixel (its first three inputs).
    Vec3 position(size_t pixel) const {
        const float* r = input(pixel);
        return Vec3(r[0], r[1], r[2]);
    }
    bool covered(size_t pixel) const { return object[pixel] >= 0; }
};

/// Builds the G-buffer of `tracer`'s scene seen by its camera at width × height, with the movable
/// light's centre at `lightPos` (the tracer's own light for scenes without a movable light).
/// Parallel over rows (oneTBB); the result does not depend on the thread count.
GBuffer buildGBuffer(const PathTracer& tracer, const RecordLayout& layout, const Vec3& lightPos, int width, int height);

/// Rays per row of buildGBufferFromRays' buffer.
constexpr size_t kRaysPerRow = 1024;
/// The same records for arbitrary rays: sample i (pixel i of a buffer kRaysPerRow wide, the last row
/// padded with background; empty rays give 0 × 0) is what rays[i] hits, its view direction
/// −rays[i].dir. A ray with tmax ≤ tmin is not traced (the sample stays background). The glossy
/// gather's secondary hits (core/predict/glossy_gather.h).
GBuffer buildGBufferFromRays(const PathTracer& tracer, const RecordLayout& layout, const Vec3& lightPos,
                             const std::vector<Ray>& rays);

}  // namespace rrf
