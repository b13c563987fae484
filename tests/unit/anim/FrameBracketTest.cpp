#include "runtime/anim/FrameBracket.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace kiosk::anim {
namespace {

constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();
// Irregular spacing: 10 s, 20 s, 40 s.
const std::vector<double> kTimes = {100.0, 110.0, 130.0, 170.0};

TEST(FrameBracket, ExactlyOnAFrameNeedsOnlyThatFrame) {
    for (std::size_t k = 0; k < kTimes.size(); ++k) {
        const auto b = bracketFrames(kTimes, kTimes[k], Interpolation::Data);
        EXPECT_TRUE(b.valid);
        EXPECT_EQ(b.i0, k);
        EXPECT_EQ(b.i1, k);
        EXPECT_EQ(b.alpha, 0.0);
        EXPECT_FALSE(b.beforeFirst);
        EXPECT_FALSE(b.afterLast);
    }
}

TEST(FrameBracket, BetweenIrregularFrames) {
    auto b = bracketFrames(kTimes, 115.0, Interpolation::Data);
    EXPECT_EQ(b.i0, 1u);
    EXPECT_EQ(b.i1, 2u);
    EXPECT_DOUBLE_EQ(b.alpha, 0.25);
    b = bracketFrames(kTimes, 160.0, Interpolation::Data);
    EXPECT_EQ(b.i0, 2u);
    EXPECT_EQ(b.i1, 3u);
    EXPECT_DOUBLE_EQ(b.alpha, 0.75);
    b = bracketFrames(kTimes, 105.0, Interpolation::Arrival);
    EXPECT_EQ(b.i0, 0u);
    EXPECT_EQ(b.i1, 1u);
    EXPECT_DOUBLE_EQ(b.alpha, 0.5);
    // Just below the next frame alpha stays below 1 (the pair is still (k, k+1)).
    b = bracketFrames(kTimes, std::nextafter(170.0, 0.0), Interpolation::Data);
    EXPECT_EQ(b.i0, 2u);
    EXPECT_LT(b.alpha, 1.0);
    EXPECT_GT(b.alpha, 0.999999);
}

TEST(FrameBracket, ClampsBeforeAndAfter) {
    auto b = bracketFrames(kTimes, 50.0, Interpolation::Data);
    EXPECT_TRUE(b.valid);
    EXPECT_TRUE(b.beforeFirst);
    EXPECT_EQ(b.i0, 0u);
    EXPECT_EQ(b.i1, 0u);
    EXPECT_EQ(b.alpha, 0.0);
    b = bracketFrames(kTimes, 1e12, Interpolation::Data);
    EXPECT_TRUE(b.afterLast);
    EXPECT_EQ(b.i0, 3u);
    EXPECT_EQ(b.i1, 3u);
    EXPECT_EQ(b.alpha, 0.0);
}

TEST(FrameBracket, NoneAndSwitchGiveTheFrameAtOrBefore) {
    for (auto mode : {Interpolation::None, Interpolation::Categorical}) {
        auto b = bracketFrames(kTimes, 129.9, mode);
        EXPECT_EQ(b.i0, 1u);
        EXPECT_EQ(b.i1, 1u);
        EXPECT_EQ(b.alpha, 0.0);
        b = bracketFrames(kTimes, 130.0, mode);
        EXPECT_EQ(b.i0, 2u);
        b = bracketFrames(kTimes, 10.0, mode);
        EXPECT_EQ(b.i0, 0u);
        EXPECT_TRUE(b.beforeFirst);
    }
}

TEST(FrameBracket, DegenerateInputs) {
    EXPECT_FALSE(bracketFrames({}, 5.0, Interpolation::Data).valid);
    EXPECT_FALSE(
        bracketFrames(kTimes, std::numeric_limits<double>::quiet_NaN(), Interpolation::Data).valid);
    const std::vector<double> one = {42.0};
    for (double t : {0.0, 42.0, 99.0}) {
        const auto b = bracketFrames(one, t, Interpolation::Data);
        EXPECT_TRUE(b.valid);
        EXPECT_EQ(b.i0, 0u);
        EXPECT_EQ(b.i1, 0u);
    }
}

TEST(FrameBracket, AlphaWithinClamps) {
    EXPECT_DOUBLE_EQ(alphaWithin(kTimes, 1, 2, 125.0), 0.75);
    EXPECT_DOUBLE_EQ(alphaWithin(kTimes, 1, 2, 500.0), 1.0);
    EXPECT_DOUBLE_EQ(alphaWithin(kTimes, 1, 2, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(alphaWithin(kTimes, 2, 2, 150.0), 0.0);
    EXPECT_DOUBLE_EQ(alphaWithin(kTimes, 1, 9, 150.0), 0.0);
}

TEST(InterpolateValue, DataMixesValuesLikeGlslMix) {
    // The example: 0.4 m between 0.2 and 0.6 at the midpoint.
    EXPECT_FLOAT_EQ(interpolateValue(0.2f, 0.6f, 0.5f, Interpolation::Data, 0.0f), 0.4f);
    for (float a : {0.0f, 0.1f, 0.33f, 0.5f, 0.9f, 1.0f}) {
        const float v0 = 1.7f, v1 = -3.25f;
        EXPECT_EQ(interpolateValue(v0, v1, a, Interpolation::Data, std::nullopt),
                  v0 * (1.0f - a) + v1 * a)
            << a;
    }
    // Out-of-range and non-finite alpha.
    EXPECT_EQ(interpolateValue(1.0f, 2.0f, 7.0f, Interpolation::Data, std::nullopt), 2.0f);
    EXPECT_EQ(interpolateValue(1.0f, 2.0f, kNoData, Interpolation::Data, std::nullopt), 1.0f);
}

TEST(InterpolateValue, NodataFrontAdvancesSmoothly) {
    // A 1-D valley cross-section: frame 0 wet on x < 3, frame 1 wet on x < 6 (NaN = dry).
    const std::vector<float> f0 = {0.9f, 0.6f, 0.3f, kNoData, kNoData, kNoData, kNoData};
    const std::vector<float> f1 = {1.5f, 1.2f, 0.9f, 0.6f, 0.4f, 0.2f, kNoData};
    std::vector<float> previous(f0.size(), 0.0f);
    int previousWet = 0;
    for (int step = 0; step <= 100; ++step) {
        const float a = static_cast<float>(step) / 100.0f;
        int wet = 0;
        for (std::size_t x = 0; x < f0.size(); ++x) {
            const float v = interpolateValue(f0[x], f1[x], a, Interpolation::Data, 0.0f);
            if (x == 6) {
                EXPECT_TRUE(std::isnan(v)) << "nodata on both sides stays nodata";
                continue;
            }
            ASSERT_FALSE(std::isnan(v)) << "x=" << x << " a=" << a;
            const float d0 = std::isnan(f0[x]) ? 0.0f : f0[x];
            EXPECT_FLOAT_EQ(v, d0 * (1.0f - a) + f1[x] * a);
            // Smooth: no pixel jumps by more than its own frame difference times the step.
            if (step > 0) {
                EXPECT_LE(std::fabs(v - previous[x]), std::fabs(f1[x] - d0) * 0.0101f + 1e-6f);
            }
            previous[x] = v;
            wet += v > 0.0f ? 1 : 0;
        }
        EXPECT_GE(wet, previousWet) << "the wet area never shrinks while the flood rises";
        previousWet = wet;
    }
    EXPECT_EQ(previousWet, 6);
}

TEST(InterpolateValue, OneSidedNodataWithoutDeclaredValueSwitchesAtHalf) {
    EXPECT_TRUE(std::isnan(interpolateValue(kNoData, 2.0f, 0.49f, Interpolation::Data, {})));
    EXPECT_EQ(interpolateValue(kNoData, 2.0f, 0.5f, Interpolation::Data, {}), 2.0f);
    EXPECT_EQ(interpolateValue(2.0f, kNoData, 0.2f, Interpolation::Data, {}), 2.0f);
}

TEST(InterpolateValue, NoneIsTheRawStep) {
    EXPECT_EQ(interpolateValue(0.2f, 0.6f, 0.9f, Interpolation::None, 0.0f), 0.2f);
    EXPECT_TRUE(std::isnan(interpolateValue(kNoData, 0.6f, 0.9f, Interpolation::None, 0.0f)));
}

TEST(InterpolateValue, CategoricalNeverBlends) {
    for (float a : {0.0f, 0.25f, 0.5f, 0.999f})
        EXPECT_EQ(interpolateValue(1.0f, 3.0f, a, Interpolation::Categorical, {}), 1.0f);
    EXPECT_EQ(interpolateValue(1.0f, 3.0f, 1.0f, Interpolation::Categorical, {}), 3.0f);
    EXPECT_EQ(interpolateValue(kNoData, 3.0f, 0.3f, Interpolation::Categorical, 0.0f), 0.0f);
}

TEST(InterpolateValue, ArrivalSwitchesEachPixelAtItsThreshold) {
    // Three pixels burning at 20 %, 50 % and 90 % of the interval (unburned = nodata -> 0).
    const float th[] = {arrivalThreshold(1002.0, 1000.0, 1010.0),
                        arrivalThreshold(1005.0, 1000.0, 1010.0),
                        arrivalThreshold(1009.0, 1000.0, 1010.0)};
    EXPECT_FLOAT_EQ(th[0], 0.2f);
    EXPECT_FLOAT_EQ(th[2], 0.9f);
    for (int step = 0; step <= 10; ++step) {
        const float a = static_cast<float>(step) / 10.0f;
        for (int p = 0; p < 3; ++p) {
            const float v = interpolateValue(kNoData, 2.0f, a, Interpolation::Arrival, 0.0f, th[p]);
            EXPECT_EQ(v, a >= th[p] ? 2.0f : 0.0f) << "p=" << p << " a=" << a;
        }
    }
    // Unknown arrival switches at the next frame; bad intervals give 0.
    EXPECT_EQ(arrivalThreshold(std::nan(""), 0.0, 10.0), 1.0f);
    EXPECT_EQ(arrivalThreshold(5.0, 10.0, 10.0), 0.0f);
    EXPECT_EQ(arrivalThreshold(-5.0, 0.0, 10.0), 0.0f);
    EXPECT_EQ(interpolateValue(1.0f, 2.0f, 0.7f, Interpolation::Arrival, {}, kNoData), 1.0f);
}

TEST(Interpolation, Names) {
    EXPECT_EQ(parseInterpolation("data"), Interpolation::Data);
    EXPECT_EQ(parseInterpolation("none"), Interpolation::None);
    EXPECT_EQ(parseInterpolation("switch"), Interpolation::Categorical);
    EXPECT_EQ(parseInterpolation("categorical"), Interpolation::Categorical);
    EXPECT_EQ(parseInterpolation("arrival"), Interpolation::Arrival);
    EXPECT_FALSE(parseInterpolation("linear").has_value());
    EXPECT_STREQ(toString(Interpolation::Arrival), "arrival");
}

}  // namespace
}  // namespace kiosk::anim
