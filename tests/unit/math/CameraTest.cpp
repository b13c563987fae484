#include "runtime/math/Camera.h"

#include <gtest/gtest.h>

#include "runtime/math/Frustum.h"

namespace kiosk::math {

TEST(CameraTest, ViewpointLooksAtTarget) {
    Viewpoint vp{glm::dvec3(1000.0, 2000.0, 100.0), 90.0, -30.0, 500.0};
    Camera c = Camera::fromViewpoint(vp, 1280, 720);
    EXPECT_NEAR(glm::distance(c.eye, vp.target), 500.0, 1e-9);
    // Heading 90 = looking east, so the eye is west of the target and above it.
    EXPECT_LT(c.eye.x, vp.target.x);
    EXPECT_GT(c.eye.z, vp.target.z);
    // The target projects to the screen centre.
    glm::dvec4 clip = c.projection() * c.view() * glm::dvec4(vp.target, 1.0);
    EXPECT_NEAR(clip.x / clip.w, 0.0, 1e-9);
    EXPECT_NEAR(clip.y / clip.w, 0.0, 1e-9);
}

TEST(CameraTest, PixelsPerMetreMatchesProjection) {
    Camera c = Camera::fromViewpoint({glm::dvec3(0.0), 0.0, 0.0, 1000.0}, 1000, 800);
    // A 1 m vertical segment at the target, seen face-on, spans this many pixels.
    glm::dmat4 vp = c.projection() * c.view();
    glm::dvec4 a = vp * glm::dvec4(0.0, 0.0, 0.0, 1.0), b = vp * glm::dvec4(0.0, 0.0, 1.0, 1.0);
    double pixels = (b.y / b.w - a.y / a.w) * 0.5 * 800.0;
    EXPECT_NEAR(pixels, c.pixelsPerMetreAt(1000.0), 1e-6);
}

TEST(FrustumTest, CullsBoxesOutside) {
    Camera c = Camera::fromViewpoint({glm::dvec3(0.0), 0.0, -45.0, 1000.0}, 1280, 720);
    Frustum f(c.projection() * c.view());
    EXPECT_TRUE(f.intersects({glm::dvec3(-10.0), glm::dvec3(10.0)}));
    EXPECT_FALSE(f.intersects({glm::dvec3(-10.0, -5000.0, -10.0), glm::dvec3(10.0, -4000.0, 10.0)}));
    EXPECT_FALSE(f.intersects({glm::dvec3(50000.0, 0.0, 0.0), glm::dvec3(50010.0, 10.0, 10.0)}));
}

TEST(AabbTest, Distance) {
    Aabb b{glm::dvec3(0.0), glm::dvec3(10.0)};
    EXPECT_EQ(b.distanceTo(glm::dvec3(5.0)), 0.0);
    EXPECT_DOUBLE_EQ(b.distanceTo(glm::dvec3(13.0, 14.0, 5.0)), 5.0);
}

}  // namespace kiosk::math
