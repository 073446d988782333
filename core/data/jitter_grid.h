#pragma once
/// Jittered viewpoint grid of the data generator (docs/design.md §8): the scene bounds split into
/// Nx × Ny × Nz cells with one uniformly random viewpoint per cell, so that every region of the scene
/// is seen from nearby — 200 unstructured viewpoints left corners of the scene without data.
///
/// Viewpoints that would produce useless records are dropped:
///  - inside a closed object (box, sphere, or a mesh flagged "closed"): decided by ray parity — along
///    each of 14 probe directions the crossings of each closed object are counted, and the point is
///    inside when a majority of probes cross some closed object an odd number of times. Parity does
///    not depend on how the mesh is wound, and the majority vote survives a probe grazing an edge;
///  - outside the scene: more than 3/4 of the probes escape without hitting anything (the point sees
///    almost nothing of the scene, e.g. beyond an open side). A point in an open room corner or above
///    a ground plane sees geometry in at least half the directions and is kept;
///  - behind a surface: more than half of the probes that hit an object hit the BACK of an open
///    surface (a quad or mesh not flagged closed, seen against its front normal, docs/file-formats.md).
///    Such a point lies behind the scene's walls or under its floor, where no camera of the scene
///    stands: in the Cornell box the tall block reaches 1 cm below the floor, so the grid has a slab
///    of viewpoints under it whose records would be the floor's underside and the blocks' bottom
///    faces. A free-standing card seen from behind inside a room is a minority of the probes and
///    does not drop the point.

#include <cstdint>

#include "core/render/path_tracer.h"

namespace rrf {

class JitterGrid {
public:
    JitterGrid(const Bounds3& bounds, int nx, int ny, int nz) : bounds_(bounds), nx_(nx), ny_(ny), nz_(nz) {}

    int cellCount() const { return nx_ * ny_ * nz_; }
    /// Cell index → (ix, iy, iz), x fastest.
    void cellCoords(int cell, int& ix, int& iy, int& iz) const {
        ix = cell % nx_;
        iy = (cell / nx_) % ny_;
        iz = cell / (nx_ * ny_);
    }
    /// The uniformly random viewpoint of `cell` for `seed` (a pure function of both).
    Vec3 viewpoint(int cell, uint64_t seed) const;
    const Bounds3& bounds() const { return bounds_; }

private:
    Bounds3 bounds_;
    int nx_, ny_, nz_;
};

enum class ViewpointStatus { Kept, InsideObject, OutsideScene, BehindSurface };

/// Decides whether a viewpoint is kept (see the file comment). Thread-safe.
class ViewpointClassifier {
public:
    explicit ViewpointClassifier(const PathTracer& tracer) : tracer_(tracer) {}
    ViewpointStatus classify(const Vec3& p) const;

private:
    const PathTracer& tracer_;
};

}  // namespace rrf
