// Occlusion culling's pure plan (docs/terrain.md §10): when batches start, and the conservative
// query box (enlarged past depth and rasterisation noise, refused at the near plane).
#include "runtime/terrain/OcclusionPlan.h"

#include <gtest/gtest.h>

namespace kiosk::terrain {
namespace {

math::Camera lookingNorth() {
    math::Camera c;
    c.eye = glm::dvec3(0.0, 0.0, 100.0);
    c.forward = glm::dvec3(0.0, 1.0, 0.0);
    c.up = glm::dvec3(0.0, 0.0, 1.0);
    c.nearPlane = 10.0;
    c.farPlane = 200000.0;
    return c;
}

TEST(OcclusionPlan, RoundsStartAfterTheNearestQuarter) {
    EXPECT_TRUE(OcclusionPlan::roundStarts(OcclusionPlan::kMinTiles - 1).empty());
    const auto s = OcclusionPlan::roundStarts(40);
    ASSERT_EQ(s.size(), std::size_t(OcclusionPlan::kRounds));
    EXPECT_EQ(s, (std::vector<std::size_t>{10, 20, 30}));
    const auto few = OcclusionPlan::roundStarts(OcclusionPlan::kMinTiles);
    for (std::size_t i = 1; i < few.size(); ++i) EXPECT_GT(few[i], few[i - 1]);
    EXPECT_GE(few.front(), 1u) << "the nearest tile is always an untested occluder";
}

TEST(OcclusionPlan, BoxContainsTheTileWithAMarginGrowingWithDistance) {
    const math::Camera cam = lookingNorth();
    const math::Aabb nearTile{glm::dvec3(-100, 900, 0), glm::dvec3(100, 1100, 50)};
    const math::Aabb farTile{glm::dvec3(-100, 99900, 0), glm::dvec3(100, 100100, 50)};
    const auto a = OcclusionPlan::queryBox(cam, nearTile, 1.0);
    const auto b = OcclusionPlan::queryBox(cam, farTile, 1.0);
    ASSERT_TRUE(a && b);
    for (const auto& [box, tile] : {std::pair{*a, nearTile}, std::pair{*b, farTile}}) {
        EXPECT_TRUE(glm::all(glm::lessThan(box.min, tile.min)));
        EXPECT_TRUE(glm::all(glm::greaterThan(box.max, tile.max)));
    }
    const double marginNear = nearTile.min.x - a->min.x, marginFar = farTile.min.x - b->min.x;
    EXPECT_GE(marginNear, 1.0);
    // 8 depth steps of 24 bits at 100.1 km with a 10 m near plane: about 480 m.
    EXPECT_GT(marginFar, 400.0);
    EXPECT_GT(marginFar, 100.0 * marginNear);
}

TEST(OcclusionPlan, BoxesAtTheNearPlaneOrAroundTheEyeAreNotTested) {
    const math::Camera cam = lookingNorth();
    EXPECT_FALSE(
        OcclusionPlan::queryBox(cam, {glm::dvec3(-50, -50, 0), glm::dvec3(50, 50, 200)}, 1.0));
    // Beyond the near plane, but the margin reaches it.
    EXPECT_FALSE(
        OcclusionPlan::queryBox(cam, {glm::dvec3(-50, 10.5, 0), glm::dvec3(50, 60, 50)}, 1.0));
    EXPECT_TRUE(
        OcclusionPlan::queryBox(cam, {glm::dvec3(-50, 20, 0), glm::dvec3(50, 60, 50)}, 1.0));
    // Entirely behind the eye: its depth is negative, never tested (the frustum culls it).
    EXPECT_FALSE(
        OcclusionPlan::queryBox(cam, {glm::dvec3(-50, -900, 0), glm::dvec3(50, -800, 50)}, 1.0));
}

}  // namespace
}  // namespace kiosk::terrain
