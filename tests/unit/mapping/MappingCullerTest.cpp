// Per-frame culling of projective mappings: view frustum, then the paper's screen-space size
// rho = (w / phi) * |U||V| / |O - COP| < t.
#include "runtime/mapping/MappingCuller.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kiosk::mapping {
namespace {

class MappingCullerTest : public ::testing::Test {
protected:
    void SetUp() override {
        // Looking straight down at (5000, 5000) from 4 km; 1280x720, 45° vertical.
        mCamera = math::Camera::fromViewpoint({{5000, 5000, 0}, 0.0, -89.9, 4000.0}, 1280, 720);
        mCamera.fitClipPlanes({0, 0, 0}, {10000, 10000, 500});
        mFrustum = math::Frustum(mCamera.projection() * mCamera.view());
        mOptions.zMin = 0;
        mOptions.zMax = 500;
        mOptions.sceneScale = 5000;
    }

    static MappingState square(glm::dvec3 o, double side) {
        MappingState s;
        s.origin = o;
        s.u = {side, 0, 0};
        s.v = {0, side, 0};
        return s;
    }

    math::Camera mCamera;
    math::Frustum mFrustum;
    CullOptions mOptions;
};

TEST_F(MappingCullerTest, RhoFollowsThePaperFormula) {
    const auto s = square({5000, 5000, 0}, 500);
    const double hfov =
        glm::degrees(2.0 * std::atan(std::tan(glm::radians(45.0) / 2.0) * mCamera.aspect));
    const double d = glm::length(s.origin - mCamera.eye) / 5000.0;
    const double expected = 1280.0 / hfov * (0.1 * 0.1) / d;
    EXPECT_NEAR(screenSizeRho(s, mCamera, 5000.0), expected, 1e-12);
    // Quarter the area -> a quarter of rho; double the distance -> half.
    EXPECT_NEAR(screenSizeRho(square({5000, 5000, 0}, 250), mCamera, 5000.0), expected / 4, 1e-12);
}

TEST_F(MappingCullerTest, OnScreenLargeMappingIsActive) {
    EXPECT_EQ(cull(square({5000, 5000, 0}, 500), mCamera, mFrustum, mOptions), CullResult::Active);
}

TEST_F(MappingCullerTest, OffScreenMappingIsFrustumCulled) {
    EXPECT_EQ(cull(square({30000, 5000, 0}, 500), mCamera, mFrustum, mOptions),
              CullResult::Frustum);
    EXPECT_EQ(cull(square({5000, -20000, 0}, 500), mCamera, mFrustum, mOptions),
              CullResult::Frustum);
}

TEST_F(MappingCullerTest, RectangleAboveTheTerrainStillCoversItFromBelowTheView) {
    // The rectangle's plane lies far above the camera, but it projects onto visible terrain.
    EXPECT_EQ(cull(square({5000, 5000, 20000}, 500), mCamera, mFrustum, mOptions),
              CullResult::Active);
}

TEST_F(MappingCullerTest, TinyMappingIsSizeCulled) {
    // 2 m square at 4 km: well under a pixel.
    const auto tiny = square({5000, 5000, 0}, 2);
    EXPECT_LT(screenSizeRho(tiny, mCamera, 5000.0), mOptions.sizeThreshold);
    EXPECT_EQ(cull(tiny, mCamera, mFrustum, mOptions), CullResult::Size);
    // The paper's t = 0.02 culls much more: a 100 m square survives 1e-4 but not 0.02.
    const auto mid = square({5000, 5000, 0}, 100);
    EXPECT_EQ(cull(mid, mCamera, mFrustum, mOptions), CullResult::Active);
    CullOptions paper = mOptions;
    paper.sizeThreshold = 0.02;
    EXPECT_EQ(cull(mid, mCamera, mFrustum, paper), CullResult::Size);
}

TEST_F(MappingCullerTest, DisabledAndDegenerateAreCountedApart) {
    auto off = square({5000, 5000, 0}, 500);
    off.enabled = false;
    auto clear = square({5000, 5000, 0}, 500);
    clear.opacity = 0.0;
    auto flat = square({5000, 5000, 0}, 500);
    flat.v = flat.u;
    EXPECT_EQ(cull(off, mCamera, mFrustum, mOptions), CullResult::Disabled);
    EXPECT_EQ(cull(clear, mCamera, mFrustum, mOptions), CullResult::Disabled);
    EXPECT_EQ(cull(flat, mCamera, mFrustum, mOptions), CullResult::Degenerate);
    MappingCounts c;
    for (auto r : {CullResult::Active, CullResult::Frustum, CullResult::Frustum, CullResult::Size,
                   CullResult::Degenerate})
        c.add(r);
    EXPECT_EQ(c.active, 1u);
    EXPECT_EQ(c.culledFrustum, 2u);
    EXPECT_EQ(c.culledSize, 1u);
    EXPECT_EQ(c.disabled, 1u);
}

}  // namespace
}  // namespace kiosk::mapping
