// The paper's way-point and edge mappings for route highlighting (§5.1).
#include "runtime/mapping/RouteMappings.h"

#include <gtest/gtest.h>

namespace kiosk::mapping {
namespace {

TEST(RouteMappingsTest, EdgesThenPoints) {
    MappingState base;
    base.opacity = 0.8;
    const std::vector<glm::dvec2> pts{{0, 0}, {300, 0}, {300, 400}, {300, 400}};
    auto pieces = routeMappings(base, pts, 20.0, 15.0);
    ASSERT_EQ(pieces.size(), 2u + 4u);  // the repeated point makes no edge
    const auto& e0 = pieces[0].state;
    EXPECT_EQ(pieces[0].kind, RoutePieceKind::Edge);
    EXPECT_DOUBLE_EQ(e0.origin.x, 150.0);
    EXPECT_DOUBLE_EQ(glm::length(e0.u), 320.0);  // segment + width
    EXPECT_DOUBLE_EQ(glm::length(e0.v), 20.0);
    EXPECT_NEAR(glm::dot(e0.u, e0.v), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(e0.opacity, 0.8);
    const auto& e1 = pieces[1].state;
    EXPECT_DOUBLE_EQ(e1.origin.y, 200.0);
    EXPECT_GT(glm::cross(e1.u, e1.v).z, 0.0);  // N = +z: the plane faces up
    EXPECT_EQ(pieces[2].kind, RoutePieceKind::Point);
    EXPECT_DOUBLE_EQ(pieces[3].state.origin.x, 300.0);
    EXPECT_DOUBLE_EQ(glm::length(pieces[3].state.u), 30.0);
    EXPECT_TRUE(routeMappings(base, pts, 20.0, 0.0).size() == 2u);
    EXPECT_TRUE(routeMappings(base, {{1, 1}}, 20.0, 0.0).empty());
}

TEST(RouteMappingsTest, ProceduralTexturesHaveTheirProfiles) {
    const int n = 64;
    auto edge = edgeProfileImage(n);
    ASSERT_EQ(edge.size(), std::size_t(n * n * 4));
    auto alpha = [&](const std::vector<std::uint8_t>& img, int x, int y) {
        return int(img[(std::size_t(y) * n + std::size_t(x)) * 4 + 3]);
    };
    EXPECT_EQ(alpha(edge, 10, n / 2), 255);
    EXPECT_EQ(alpha(edge, 50, n / 2), 255);
    EXPECT_EQ(alpha(edge, 10, 0), 0);
    EXPECT_EQ(alpha(edge, 10, n - 1), 0);
    auto disc = discImage(n);
    EXPECT_EQ(alpha(disc, n / 2, n / 2), 255);
    EXPECT_EQ(alpha(disc, 0, 0), 0);
    EXPECT_EQ(alpha(disc, n / 2, 0), 0);
}

}  // namespace
}  // namespace kiosk::mapping
