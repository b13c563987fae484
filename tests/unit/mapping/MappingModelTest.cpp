// Projective mapping evaluation: the plane -> texture transform (Trapp & Döllner §3.1) and keyed
// parameters over the clock.
#include "runtime/mapping/MappingModel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kiosk::mapping {
namespace {

void expectNear(glm::dvec2 a, glm::dvec2 b, double eps = 1e-9) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
}

MappingState rect(glm::dvec3 o, glm::dvec3 u, glm::dvec3 v) {
    MappingState s;
    s.origin = o;
    s.u = u;
    s.v = v;
    return s;
}

TEST(MappingModelTest, CentreAndCornersMapToUnitSquare) {
    const auto s = rect({1000, 2000, 50}, {200, 0, 0}, {0, 100, 0});
    const glm::dvec3 sceneOrigin(900, 1900, 0);
    auto t = textureTransform(s, sceneOrigin);
    ASSERT_TRUE(t);
    const glm::dvec3 o = s.origin - sceneOrigin;
    expectNear(t->apply(o), {0.5, 0.5});
    expectNear(t->apply(o + glm::dvec3(100, 50, 0)), {1.0, 1.0});
    expectNear(t->apply(o + glm::dvec3(-100, -50, 0)), {0.0, 0.0});
    expectNear(t->apply(o + glm::dvec3(50, 0, 0)), {0.75, 0.5});
    // Orthographic along N = U x V: height does not move the texture coordinate.
    expectNear(t->apply(o + glm::dvec3(50, 0, 3000)), {0.75, 0.5});
    EXPECT_TRUE(testAABB2D(t->rect(o + glm::dvec3(99, 49, 0))));
    EXPECT_FALSE(testAABB2D(t->rect(o + glm::dvec3(101, 0, 0))));
    EXPECT_FALSE(testAABB2D(t->rect(o + glm::dvec3(0, -51, 0))));
}

TEST(MappingModelTest, RotatedAndSkewedAxesUseTheDualBasis) {
    // U rotated 90°: s runs north, t runs west.
    auto t = textureTransform(rect({0, 0, 0}, {0, 10, 0}, {-20, 0, 0}), glm::dvec3(0.0));
    ASSERT_TRUE(t);
    expectNear(t->apply({0, 5, 0}), {1.0, 0.5});
    expectNear(t->apply({-10, 0, 0}), {0.5, 1.0});
    // Non-orthogonal axes: the corner O + U/2 + V/2 still lands on (1, 1).
    const auto skew = rect({5, 5, 0}, {10, 0, 0}, {4, 10, 0});
    auto ts = textureTransform(skew, glm::dvec3(0.0));
    ASSERT_TRUE(ts);
    expectNear(ts->apply(skew.origin + 0.5 * skew.u + 0.5 * skew.v), {1.0, 1.0});
    expectNear(ts->apply(skew.origin - 0.5 * skew.u + 0.5 * skew.v), {0.0, 1.0});
}

TEST(MappingModelTest, TextureMatrixSelectsAnAtlasCell) {
    // M_T = scale 1/4 then offset (0.5, 0.25): the rectangle shows atlas cell (2, 1) of 4x4.
    auto s = rect({0, 0, 0}, {8, 0, 0}, {0, 8, 0});
    s.textureMatrix = toGlm(config::Mat3{0.25, 0, 0.5, 0, 0.25, 0.25, 0, 0, 1});
    auto t = textureTransform(s, glm::dvec3(0.0));
    ASSERT_TRUE(t);
    expectNear(t->apply({-4, -4, 0}), {0.5, 0.25});
    expectNear(t->apply({4, 4, 0}), {0.75, 0.5});
    // The footprint stays the rectangle: 2 m beyond its edge M_T would still give a coordinate
    // inside [0,1]², but the rectangle coordinate fails testAABB2D.
    EXPECT_TRUE(testAABB2D(t->apply({6, 0, 0})));
    EXPECT_FALSE(testAABB2D(t->rect({6, 0, 0})));
    // A projective M_T divides by w.
    s.textureMatrix = toGlm(config::Mat3{1, 0, 0, 0, 1, 0, 0, 0, 2});
    auto p = textureTransform(s, glm::dvec3(0.0));
    ASSERT_TRUE(p);
    expectNear(p->apply({4, 4, 0}), {0.5, 0.5});
}

TEST(MappingModelTest, DegenerateAxesHaveNoTransform) {
    EXPECT_FALSE(textureTransform(rect({0, 0, 0}, {1, 0, 0}, {2, 0, 0}), glm::dvec3(0.0)));
    EXPECT_FALSE(textureTransform(rect({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), glm::dvec3(0.0)));
}

TEST(MappingModelTest, RowMajorMatricesConvert) {
    const glm::dmat4 m = toGlm(config::Mat4{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16});
    const glm::dvec4 r = m * glm::dvec4(1, 0, 0, 1);  // column 0 + column 3
    EXPECT_DOUBLE_EQ(r.x, 1 + 4);
    EXPECT_DOUBLE_EQ(r.y, 5 + 8);
    EXPECT_DOUBLE_EQ(r.w, 13 + 16);
}

config::MappingKey key(double t) {
    config::MappingKey k;
    k.time.isOffset = true;
    k.time.seconds = t;
    return k;
}

TEST(MappingModelTest, KeysInterpolateOverTheClock) {
    config::ProjectiveMapping m;
    m.origin = {0, 0, 0};
    m.u = {100, 0, 0};
    m.v = {0, 100, 0};
    m.opacity = 1.0;
    auto k0 = key(10);
    k0.origin = config::Vec3{0, 0, 0};
    k0.opacity = 0.0;
    auto k1 = key(20);
    k1.origin = config::Vec3{1000, 500, 0};
    k1.u = config::Vec3{0, 100, 0};  // quarter turn
    k1.v = config::Vec3{-100, 0, 0};
    k1.opacity = 1.0;
    m.keys = {k0, k1};
    const double start = 1000.0;

    auto before = evaluate(m, start + 0.0, start);  // the first key holds before its time
    EXPECT_NEAR(before.opacity, 0.0, 1e-12);
    auto mid = evaluate(m, start + 15.0, start);
    EXPECT_NEAR(mid.origin.x, 500.0, 1e-9);
    EXPECT_NEAR(mid.origin.y, 250.0, 1e-9);
    EXPECT_NEAR(mid.opacity, 0.5, 1e-12);
    // Direction slerped, length kept: 45° at full size (lerp would give 70.7 m).
    EXPECT_NEAR(glm::length(mid.u), 100.0, 1e-9);
    EXPECT_NEAR(mid.u.x, 100.0 / std::sqrt(2.0), 1e-9);
    EXPECT_NEAR(mid.u.y, 100.0 / std::sqrt(2.0), 1e-9);
    auto after = evaluate(m, start + 99.0, start);
    EXPECT_NEAR(after.origin.x, 1000.0, 1e-12);
    EXPECT_NEAR(after.u.y, 100.0, 1e-12);
    // Keys without a field keep what was reached: u of k0 is the base u.
    auto atK0 = evaluate(m, start + 10.0, start);
    EXPECT_NEAR(atK0.u.x, 100.0, 1e-12);
}

}  // namespace
}  // namespace kiosk::mapping
