#pragma once
/// Affine transforms of scene files: scale, then rotations (in list order), then translation.
/// Evaluated in double so that composed rotations reproduce reference coordinates (e.g. the
/// Cornell box corners) to well below float precision before the result is stored as float.

#include <Eigen/Core>
#include <Eigen/LU>

#include "core/util/json_reader.h"
#include "core/util/vec3.h"

namespace rrf {

struct Transform {
    Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();

    /// Maps a point.
    Vec3 apply(const Vec3& p) const;
    /// Determinant of the linear part; negative for mirroring transforms, which flip the winding
    /// (and therefore the normals) of transformed primitives.
    double determinant() const { return linear.determinant(); }
    bool flipsOrientation() const { return determinant() < 0; }
};

/// Reads {"scale": [sx,sy,sz] | s, "rotate": {"axis": [..], "degrees": d} | [{..}, ..],
/// "translate": [..]} (all optional). Zero or non-finite scale factors and zero rotation axes are
/// rejected with an InputError at the offending member.
Transform parseTransform(const JsonReader& r);

}  // namespace rrf
