#pragma once
/// Footprint mask (docs/design.md §14): the object pixels on which a pixel-centre prediction can be
/// compared with a path-traced reference.
///
/// The reference averages a box filter over each pixel's square; the prediction evaluates the one
/// surface point seen through the pixel centre (core/predict/gbuffer.h). Both agree, up to the
/// reference's noise and the second-order variation of smooth shading across the square, only where
/// the square shows one smooth surface. Elsewhere the difference measures the filter, not the model
/// (at a box's creases it dwarfs the images' own noise: docs/results-history.md, §14). So an
/// object pixel is left out of every error statistic when its footprint can cover more than one
/// surface, judged from the centre samples of its 3×3 neighbourhood: a discontinuity between two
/// neighbouring centres lies in the square of one of them, so both are left out. Reasons, tested in
/// this order (a pixel is counted under the first that applies, so the reasons add up to the total):
///
///   next to the light  an emitter pixel in the 3×3 neighbourhood (its radiance is far above any
///                      surface's, so a sliver of it dominates the pixel);
///   object edge        another object id or the background in the neighbourhood;
///   normal edge        a neighbour's normal differs by more than kFootprintNormalDegrees;
///   depth step         a neighbour's hit point lies off the pixel's tangent plane by more than
///                      kFootprintDepthFraction of the pixel's distance from the eye (a plane behind a
///                      plane of one object). Measured off the tangent plane, not as a difference of
///                      distances, so a wall seen at a grazing angle, whose distance changes fast from
///                      pixel to pixel, stays one surface.
///
/// Neighbours outside the image are ignored: the footprint does not reach them. Emitter and background
/// pixels are never compared (the prediction copies the emitted radiance; the background is black).
/// A feature thinner than the pixel spacing that no centre ray hits is not seen by this test.

#include <cstdint>
#include <string>
#include <vector>

#include "core/predict/gbuffer.h"

namespace rrf {

/// Normals of neighbouring pixels further apart than this (degrees) mark an edge between faces. Well
/// above the float noise of one flat face's normals (< 1e-3 degrees) and below the creases the
/// scenes model; a smooth surface curving more than this per pixel is left out as well, since its
/// footprint is then no longer nearly a point of one tangent plane.
inline constexpr double kFootprintNormalDegrees = 5.0;
/// A neighbour's hit point further than this fraction of the pixel's distance from the eye off the
/// pixel's tangent plane marks a depth step. A smooth surface that passes the normal test stays within
/// about (5° in radians) × (pixel angle) / 2 ≈ 5e-4 of the distance of its tangent plane even at 64²
/// pixels, and hit points carry ~1e-6 relative float noise, so 1 % flags real steps only.
inline constexpr double kFootprintDepthFraction = 0.01;

/// Why a pixel is or is not compared.
enum class Footprint : uint8_t {
    Kept,         ///< object pixel whose footprint shows one surface: compared
    Background,   ///< the centre ray escapes: never compared
    Emitter,      ///< the centre ray sees a light: never compared
    NextToLight,  ///< object pixel with an emitter pixel in its 3×3 neighbourhood
    ObjectEdge,   ///< object pixel with another object or the background in its 3×3 neighbourhood
    NormalEdge,   ///< object pixel with a neighbour's normal more than kFootprintNormalDegrees away
    DepthStep,    ///< object pixel with a neighbour off its tangent plane (kFootprintDepthFraction)
};

/// Object pixels left out, per reason; emitter pixels for reference (never compared, not in total()).
struct FootprintCounts {
    uint64_t nextToLight = 0, objectEdge = 0, normalEdge = 0, depthStep = 0;
    uint64_t emitterPixels = 0;
    /// Object pixels left out of the statistics (each counted once, under its first reason).
    uint64_t total() const { return nextToLight + objectEdge + normalEdge + depthStep; }
    /// One line: "N object pixels left out (footprint may cover more than one surface): a next to the
    /// light, b at object edges, c at normal edges (> 5°), d at depth steps (> 1 % of distance)".
    std::string describe() const;
};

struct FootprintMask {
    int width = 0, height = 0;
    std::vector<Footprint> pixel;                    ///< reason per pixel, i = y·width + x
    std::vector<std::vector<uint32_t>> keptByObject;  ///< compared pixels per object id, ascending
    std::vector<uint32_t> kept;                      ///< all compared object pixels, ascending
    FootprintCounts counts;

    bool isKept(size_t i) const { return pixel[i] == Footprint::Kept; }
};

/// The footprint mask of `g` (rule above). Deterministic; linear in the pixel count.
FootprintMask footprintMask(const GBuffer& g);

/// Short name of a reason ("kept", "background", "emitter", "next_to_light", "object_edge",
/// "normal_edge", "depth_step") for tables, read-outs and JSON.
const char* footprintName(Footprint f);

}  // namespace rrf
