#include "runtime/math/Frustum.h"
#include "runtime/wall/ScreenFrustum.h"
#include "runtime/wall/WallReader.h"
#include "tests/unit/wall/WallTestFiles.h"

#include <gtest/gtest.h>

namespace kiosk::wall {
namespace {

Wall wall2x2() {
    auto r = parseWall(test::wall2x2(), "wall.json");
    EXPECT_TRUE(r) << r.diagnostics.format();
    return *r;
}

/** Window pixel coordinates (x right, y down, pixel centres at +0.5) of a world point. */
glm::dvec2 pixelOf(const math::Camera& c, const glm::dvec3& p) {
    const glm::dvec4 clip = c.projection() * c.view() * glm::dvec4(p, 1.0);
    const glm::dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
    return {(ndc.x + 1.0) * 0.5 * c.viewportWidth, (1.0 - ndc.y) * 0.5 * c.viewportHeight};
}

math::Camera virtualCamera(const Wall& w) {
    const glm::ivec2 size = canvasPixels(w);
    return math::Camera::fromViewpoint({glm::dvec3(500, 800, 50), 30.0, -35.0, 2000.0}, size.x,
                                       size.y, 40.0);
}

TEST(ScreenFrustumTest, EachScreenIsItsPartOfTheCanvasImage) {
    const Wall w = wall2x2();
    ASSERT_EQ(canvasPixels(w), glm::ivec2(132, 76));
    const math::Camera whole = virtualCamera(w);
    // World points seen by the whole-canvas camera land on the same canvas pixel through the
    // screen that covers it (minus the screen's offset): bezels hide, never shift, the picture.
    for (int i = 0; i < 4; ++i) {
        const Screen& s = w.screens[std::size_t(i)];
        const math::Camera sc = screenCamera(whole, w, i);
        ASSERT_TRUE(sc.window);
        EXPECT_EQ(sc.viewportWidth, 64);
        for (double fx : {0.1, 0.5, 0.93})
            for (double fy : {0.2, 0.7}) {
                // A canvas pixel inside this screen, unprojected at some depth.
                const glm::dvec2 px(s.xMm + fx * s.activeMmX, s.yMm + fy * s.activeMmY);
                const glm::dvec3 ndc(px.x / 132.0 * 2 - 1, 1 - px.y / 76.0 * 2, 0.3);
                const glm::dvec4 p =
                    glm::inverse(whole.projection() * whole.view()) * glm::dvec4(ndc, 1.0);
                const glm::dvec3 world = glm::dvec3(p) / p.w;
                const glm::dvec2 onScreen = pixelOf(sc, world);
                EXPECT_NEAR(onScreen.x, px.x - s.xMm, 1e-6) << s.id;
                EXPECT_NEAR(onScreen.y, px.y - s.yMm, 1e-6) << s.id;
            }
        // Same pixel pitch, same eye: the screen-space error bound is the same as the whole's.
        EXPECT_NEAR(sc.pixelsPerMetreAt(1234.0), whole.pixelsPerMetreAt(1234.0), 1e-9);
    }
    // The windows are asymmetric (off-axis), not cropped symmetric views.
    const math::Camera tl = screenCamera(whole, w, w.findScreen("tl"));
    EXPECT_LT(tl.window->right, 0.0);
    EXPECT_GT(tl.window->bottom, 0.0);
}

TEST(ScreenFrustumTest, CullingUsesTheScreensOwnFrustum) {
    const Wall w = wall2x2();
    const math::Camera whole = virtualCamera(w);
    // A small box at the centre of the top-right screen's image.
    const Screen& tr = w.screens[std::size_t(w.findScreen("tr"))];
    const glm::dvec3 ndc((tr.xMm + 32) / 132.0 * 2 - 1, 1 - (tr.yMm + 18) / 76.0 * 2, 0.5);
    const glm::dvec4 p = glm::inverse(whole.projection() * whole.view()) * glm::dvec4(ndc, 1.0);
    const glm::dvec3 c = glm::dvec3(p) / p.w;
    const math::Aabb box{c - 1.0, c + 1.0};
    for (int i = 0; i < 4; ++i) {
        const math::Camera sc = screenCamera(whole, w, i);
        EXPECT_EQ(math::Frustum(sc.projection() * sc.view()).intersects(box),
                  w.screens[std::size_t(i)].id == "tr")
            << w.screens[std::size_t(i)].id;
    }
}

TEST(ScreenFrustumTest, AngledScreenCornersMapToItsEdges) {
    Wall w = wall2x2();
    Screen& tr = w.screens[std::size_t(w.findScreen("tr"))];
    tr.yawDeg = 25.0;
    tr.pitchDeg = -10.0;
    tr.rollDeg = 3.0;
    const double fov = 40.0;
    const ScreenView v = screenView(w, w.findScreen("tr"), fov);
    // The basis stays orthonormal and faces the eye.
    EXPECT_NEAR(glm::dot(v.right, v.up), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(v.normal), 1.0, 1e-12);
    EXPECT_GT(v.normal.z, 0.0);
    // A flat screen's window is its rectangle over the eye distance.
    const ScreenView flat = screenView(wall2x2(), w.findScreen("tr"), fov);
    const double d = eyeDistanceMm(w, fov);
    EXPECT_NEAR(flat.window.left, (68.0 - 66.0) / d, 1e-12);
    EXPECT_NEAR(flat.window.top, 38.0 / d, 1e-12);
    // Turned, the screen covers another part of the view in its own basis.
    EXPECT_GT(std::abs(v.window.left - flat.window.left), 0.01);
    // The screen camera projects the physical corners of the turned screen to its NDC corners.
    math::Camera vc;  // identity-ish virtual camera: eye at 0 looking -z in view space
    vc.eye = glm::dvec3(0.0);
    vc.forward = glm::dvec3(0, 0, -1);
    vc.up = glm::dvec3(0, 1, 0);
    vc.fovYDeg = fov;
    vc.nearPlane = 1.0;
    vc.farPlane = 1e5;
    const math::Camera sc = screenCamera(vc, w, w.findScreen("tr"));
    glm::dmat4 rot(1.0);
    rot = glm::rotate(rot, glm::radians(25.0), glm::dvec3(0, 1, 0));
    rot = glm::rotate(rot, glm::radians(10.0), glm::dvec3(1, 0, 0));
    rot = glm::rotate(rot, glm::radians(3.0), glm::dvec3(0, 0, 1));
    const glm::dvec3 centre(68 + 32 - 66, 38 - 18, -d);
    const glm::dvec3 upperRight = centre + glm::dmat3(rot) * glm::dvec3(32, 18, 0);
    const glm::dvec4 clip = sc.projection() * sc.view() * glm::dvec4(upperRight, 1.0);
    EXPECT_NEAR(clip.x / clip.w, 1.0, 1e-9);
    EXPECT_NEAR(clip.y / clip.w, 1.0, 1e-9);
}

}  // namespace
}  // namespace kiosk::wall
