#include "runtime/anim/ArrivalThresholds.h"
#include "runtime/anim/FrameBracket.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace kiosk::anim {
namespace {

constexpr int kW = 64, kH = 64;
constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();
constexpr float kBurned = 2.0f;

// Burned disk of radius r around (32, 32); unburned is nodata (fire rasters often are).
std::vector<float> disk(double r) {
    std::vector<float> v(kW * kH, kNoData);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if (std::hypot(x - 32.0, y - 32.0) <= r) v[std::size_t(y * kW + x)] = kBurned;
    return v;
}

int burnedAt(const std::vector<float>& f0, const std::vector<float>& f1,
             const std::vector<float>& th, float alpha) {
    int n = 0;
    for (std::size_t i = 0; i < f0.size(); ++i)
        n += interpolateValue(f0[i], f1[i], alpha, Interpolation::Arrival, 0.0f, th[i]) == kBurned;
    return n;
}

TEST(ArrivalThresholds, FrontSweepsFromOldToNewPerimeter) {
    const auto f0 = disk(5.0), f1 = disk(15.0);
    std::vector<float> th;
    computeArrivalThresholds(f0, f1, kW, kH, 0.0f, th);
    ASSERT_EQ(th.size(), f0.size());
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const auto i = std::size_t(y * kW + x);
            const double r = std::hypot(x - 32.0, y - 32.0);
            if (r <= 5.0 || r > 15.0) {
                EXPECT_EQ(th[i], 0.0f) << "unchanged pixel " << x << "," << y;
            } else {
                // Radial symmetry: the threshold is the fraction of the way from r=5 to r=15.
                EXPECT_NEAR(th[i], (r - 5.0) / 10.0, 0.12) << x << "," << y;
            }
        }
    }
    // The burned area grows monotonically with alpha, never blends, and at the midpoint is
    // close to a disk of radius 10.
    int previous = 0;
    for (int s = 0; s <= 20; ++s) {
        const int n = burnedAt(f0, f1, th, static_cast<float>(s) / 20.0f);
        EXPECT_GE(n, previous);
        previous = n;
    }
    EXPECT_EQ(burnedAt(f0, f1, th, 0.0f), burnedAt(f0, f0, std::vector<float>(th.size()), 0));
    EXPECT_EQ(burnedAt(f0, f1, th, 1.0f), burnedAt(f1, f1, std::vector<float>(th.size()), 0));
    const double midArea = burnedAt(f0, f1, th, 0.5f);
    EXPECT_NEAR(midArea, M_PI * 100.0, M_PI * 100.0 * 0.15);
}

TEST(ArrivalThresholds, IgnitionSpreadsFromTheInside) {
    const auto f0 = std::vector<float>(kW * kH, kNoData), f1 = disk(10.0);
    std::vector<float> th;
    computeArrivalThresholds(f0, f1, kW, kH, 0.0f, th);
    const float centre = th[std::size_t(32 * kW + 32)];
    const float edge = th[std::size_t(32 * kW + 42)];
    EXPECT_LT(centre, 0.15f);
    EXPECT_GT(edge, 0.85f);
    EXPECT_LT(th[std::size_t(32 * kW + 36)], th[std::size_t(32 * kW + 39)]);
}

TEST(ArrivalThresholds, SeveralClassesAndBadSizes) {
    // Three classes in a strip: 0 unburned, 1 burning, 2 burned; both fronts move right.
    std::vector<float> f0(kW * kH), f1(kW * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const auto i = std::size_t(y * kW + x);
            f0[i] = x < 10 ? 2.0f : x < 20 ? 1.0f : 0.0f;
            f1[i] = x < 20 ? 2.0f : x < 30 ? 1.0f : 0.0f;
        }
    std::vector<float> th;
    computeArrivalThresholds(f0, f1, kW, kH, std::nullopt, th);
    ASSERT_EQ(th.size(), f0.size());
    for (int x = 10; x < 30; ++x) {
        // Class 2 front goes 10 -> 20, class 1 front 20 -> 30: both linear in x.
        const double expected = x < 20 ? (x - 9) / 11.0 : (x - 19) / 11.0;
        EXPECT_NEAR(th[std::size_t(5 * kW + x)], expected, 1e-6) << x;
    }
    computeArrivalThresholds(f0, f1, kW, kH - 1, 0.0f, th);
    EXPECT_TRUE(th.empty());
    computeArrivalThresholds({}, {}, 0, 0, 0.0f, th);
    EXPECT_TRUE(th.empty());
}

}  // namespace
}  // namespace kiosk::anim
