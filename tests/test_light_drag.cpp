// Moving the light by its handle in a view (core/scene/light_drag.h), checked against a pinhole
// projection written out here from the camera's definition (not core/scene/camera_rays.h): the light
// placed under a pointer projects back to that pointer, stays in its plane and in its range.
#include <cmath>

#include <gtest/gtest.h>

#include "core/scene/light_drag.h"

namespace rrf::test::test_light_drag {

namespace {
/// A camera looking into a box along -z, and a light range under the box's ceiling.
Camera camera() {
    Camera c;
    c.eye = Vec3(0.f, 1.f, 6.8f);
    c.target = Vec3(0.f, 1.f, 0.f);
    c.up = Vec3(0.f, 1.f, 0.f);
    c.fovYDegrees = 19.5f;
    return c;
}
Bounds3 range() {
    Bounds3 b;
    b.lo = Vec3(-0.6f, 1.2f, -0.6f);
    b.hi = Vec3(0.6f, 1.9f, 0.6f);
    return b;
}
constexpr int kW = 320, kH = 240;

/// Image point of `p`: pixel x grows along the camera's right, y downwards, the image spanning
/// tan(fov/2) vertically and that times the aspect ratio horizontally.
void pinhole(const Camera& c, const Vec3& p, float& x, float& y) {
    const Vec3 f = normalize(c.target - c.eye), r = normalize(cross(f, c.up)), u = cross(r, f);
    const Vec3 d = p - c.eye;
    const float t = std::tan(0.5f * c.fovYDegrees * kPi / 180.f);
    x = 0.5f * (1.f + dot(d, r) / dot(d, f) / (t * float(kW) / float(kH))) * float(kW);
    y = 0.5f * (1.f - dot(d, u) / dot(d, f) / t) * float(kH);
}
}  // namespace

TEST(LightDrag, ProjectionIsThePinholes) {
    const Vec3 p(0.3f, 1.7f, 0.2f);
    float x = 0, y = 0, ex = 0, ey = 0;
    ASSERT_TRUE(projectToImage(camera(), kW, kH, p, x, y));
    pinhole(camera(), p, ex, ey);
    EXPECT_NEAR(x, ex, 1e-3f);
    EXPECT_NEAR(y, ey, 1e-3f);
    EXPECT_FALSE(projectToImage(camera(), kW, kH, Vec3(0.f, 1.f, 9.f), x, y)) << "behind the camera";
}

TEST(LightDrag, FacingPlaneFollowsThePointer) {
    const Vec3 start(0.f, 1.5f, 0.f);
    // Points of the plane through `start` facing the camera (here z = 0), inside the range.
    for (const Vec3 target : {Vec3(0.4f, 1.8f, 0.f), Vec3(-0.5f, 1.3f, 0.f), start}) {
        float x = 0, y = 0;
        pinhole(camera(), target, x, y);
        const Vec3 p = lightUnderPointer(camera(), kW, kH, x, y, start, LightDragPlane::Facing, range());
        EXPECT_NEAR(p.x, target.x, 1e-4f);
        EXPECT_NEAR(p.y, target.y, 1e-4f);
        EXPECT_NEAR(p.z, target.z, 1e-4f);
    }
}

TEST(LightDrag, HorizontalPlaneKeepsTheHeight) {
    const Vec3 start(0.1f, 1.8f, -0.2f);
    const Vec3 target(-0.3f, 1.8f, 0.45f);
    float x = 0, y = 0;
    pinhole(camera(), target, x, y);
    const Vec3 p = lightUnderPointer(camera(), kW, kH, x, y, start, LightDragPlane::Horizontal, range());
    EXPECT_FLOAT_EQ(p.y, start.y);
    EXPECT_NEAR(p.x, target.x, 1e-3f);
    EXPECT_NEAR(p.z, target.z, 1e-3f);
}

TEST(LightDrag, TheRangeStopsTheLight) {
    const Vec3 start(0.f, 1.5f, 0.f);
    // A pointer where x = 1.4 shows on the light's plane, outside the range's x extent.
    float x = 0, y = 0;
    pinhole(camera(), Vec3(1.4f, 1.5f, 0.f), x, y);
    ASSERT_LT(x, float(kW));
    const Vec3 p = lightUnderPointer(camera(), kW, kH, x, y, start, LightDragPlane::Facing, range());
    EXPECT_FLOAT_EQ(p.x, range().hi.x);
    EXPECT_NEAR(p.y, 1.5f, 1e-4f);
}

TEST(LightDrag, APlaneTheRayCannotMeetKeepsTheStart) {
    // The horizontal plane at the eye's height, seen along it: every ray through the image's middle
    // row runs parallel to it.
    const Vec3 start(0.2f, 1.f, 0.f);
    Bounds3 wide;
    wide.lo = Vec3(-5.f);
    wide.hi = Vec3(5.f);
    const Vec3 p = lightUnderPointer(camera(), kW, kH, 100.f, float(kH) / 2, start, LightDragPlane::Horizontal, wide);
    EXPECT_EQ(p.x, start.x);
    EXPECT_EQ(p.y, start.y);
    EXPECT_EQ(p.z, start.z);
    // Above the horizon the ray meets that plane behind the camera: the start again.
    const Vec3 q = lightUnderPointer(camera(), kW, kH, 100.f, 10.f, Vec3(0.f, 0.5f, 0.f), LightDragPlane::Horizontal, wide);
    EXPECT_EQ(q.y, 0.5f);
    EXPECT_EQ(q.x, 0.f);
}

}  // namespace rrf::test::test_light_drag
