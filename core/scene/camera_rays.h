#pragma once
/// Primary rays of the pinhole camera with a box pixel filter (uniform jitter inside the pixel).
/// Image x grows along the camera's right vector, image y downwards.

#include <cmath>

#include "core/scene/accel.h"
#include "core/scene/scene.h"

namespace rrf {

class CameraRays {
public:
    CameraRays(const Camera& cam, int width, int height) : eye_(cam.eye), width_(width), height_(height) {
        forward_ = normalize(cam.target - cam.eye);
        right_ = normalize(cross(forward_, cam.up));
        up_ = cross(right_, forward_);
        const float tanHalf = std::tan(0.5f * cam.fovYDegrees * kPi / 180.f);
        right_ *= tanHalf * float(width) / float(height);
        up_ *= tanHalf;
    }

    /// Ray through image position (px + jx, py + jy), jx, jy ∈ [0,1).
    Ray generate(int px, int py, float jx, float jy) const {
        const float sx = 2.f * (float(px) + jx) / float(width_) - 1.f;
        const float sy = 1.f - 2.f * (float(py) + jy) / float(height_);
        Ray r;
        r.origin = eye_;
        r.dir = normalize(forward_ + right_ * sx + up_ * sy);
        return r;
    }

    /// Inverse of generate(): image coordinates of world direction `dir` from the eye; false if the
    /// direction points behind the camera. Used to relate data records to camera pixels.
    bool project(const Vec3& dir, float& x, float& y) const {
        const float f = dot(dir, forward_);
        if (f <= 0.f) return false;
        const float sx = dot(dir, right_) / (f * lengthSquared(right_));
        const float sy = dot(dir, up_) / (f * lengthSquared(up_));
        x = 0.5f * (sx + 1.f) * float(width_);
        y = 0.5f * (1.f - sy) * float(height_);
        return true;
    }

    int width() const { return width_; }
    int height() const { return height_; }

private:
    Vec3 eye_, forward_, right_, up_;
    int width_, height_;
};

}  // namespace rrf
