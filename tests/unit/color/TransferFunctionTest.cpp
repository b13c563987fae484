#include "runtime/color/Legend.h"
#include "runtime/color/TransferFunction.h"
#include "tests/unit/color/ColorTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace kiosk::color {
namespace {

Rgba hex(const char* h) {
    return *parseColor(h);
}

TransferFunction threeStops(Space space) {
    TransferFunction tf;
    tf.name = "t";
    tf.space = space;
    tf.stops = {{5.0, hex("#ffffff")}, {0.0, hex("#000000")}, {2.0, hex("#ff0000")}};  // unsorted
    EXPECT_FALSE(tf.finalize(false, false, false).hasErrors());
    return tf;
}

TEST(TransferFunction, FinalizeSortsAndDerivesDomain) {
    const TransferFunction tf = threeStops(Space::Srgb);
    ASSERT_EQ(tf.stops.size(), 3u);
    EXPECT_EQ(tf.stops[0].value, 0.0);
    EXPECT_EQ(tf.stops[2].value, 5.0);
    EXPECT_EQ(tf.domainMin, 0.0);
    EXPECT_EQ(tf.domainMax, 5.0);
    EXPECT_EQ(tf.below, hex("#000000"));  // defaults to the end colours
    EXPECT_EQ(tf.above, hex("#ffffff"));
}

TEST(TransferFunction, LutTexelCentresMatchTheShaderHelper) {
    // encode.glsl: (t * (n - 1) + 0.5) / n with t = (v - min) / (max - min)
    EXPECT_DOUBLE_EQ(lutCoordinate(0.0, 0.0, 5.0, 1024), 0.5 / 1024);
    EXPECT_DOUBLE_EQ(lutCoordinate(5.0, 0.0, 5.0, 1024), 1023.5 / 1024);
    EXPECT_DOUBLE_EQ(lutCoordinate(-3.0, 0.0, 5.0, 1024), 0.5 / 1024);  // clamped
    EXPECT_DOUBLE_EQ(lutCoordinate(2.5, 0.0, 5.0, 1024), 512.0 / 1024);
}

// Sampling the LUT (as GL_LINEAR would) at each stop gives the stop colour within 1 DN, in every
// interpolation space, for stops that fall between texel centres (in-gamut colours, as real
// maps use: at the gamut boundary sRGB's steep toe can amplify the curve's bend to a few DN).
TEST(TransferFunction, LutAtStopsIsExactWithinOneDn) {
    for (Space space : {Space::Srgb, Space::Linear, Space::Lab, Space::Msh}) {
        TransferFunction tf;
        tf.space = space;
        tf.stops = {{0.0, hex("#203060")},
                    {1.3, hex("#c04030")},
                    {2.0, hex("#e0d0a0c0")},
                    {5.0, hex("#f0f0e8")}};
        ASSERT_FALSE(tf.finalize(false, false, false).hasErrors());
        const auto lut = buildLut(tf, 1024);
        ASSERT_EQ(lut.size(), 4096u);
        for (const auto& s : tf.stops) {
            const auto got = test::sampleLinear(lut, lutCoordinate(tf, s.value, 1024));
            const auto want = test::dn(s.color);
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(got[std::size_t(c)], want[std::size_t(c)], 1.0)
                    << spaceName(space) << " stop " << s.value << " channel " << c;
        }
    }
}

// Stops on texel centres are reproduced exactly, even saturated primaries.
TEST(TransferFunction, StopsOnTexelCentresAreExact) {
    for (Space space : {Space::Srgb, Space::Linear, Space::Lab, Space::Msh}) {
        const TransferFunction tf = threeStops(space);  // stops 0, 2, 5
        const auto lut = buildLut(tf, 1026);            // 1025 intervals: value 2 is texel 410
        for (const auto& s : tf.stops) {
            const auto got = test::sampleLinear(lut, lutCoordinate(tf, s.value, 1026));
            const auto want = test::dn(s.color);
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(got[std::size_t(c)], want[std::size_t(c)], 1e-6) << spaceName(space);
        }
    }
}

TEST(TransferFunction, LutIsAtLeast1024AndEndsAtDomain) {
    const TransferFunction tf = threeStops(Space::Srgb);
    EXPECT_EQ(buildLut(tf, 16).size(), 4u * 1024u);
    const auto lut = buildLut(tf, 2048);
    EXPECT_EQ(lut.size(), 4u * 2048u);
    EXPECT_EQ(lut[0], 0);               // first texel = value 0 = black
    EXPECT_EQ(lut[4 * 2047 + 1], 255);  // last texel = value 5 = white
}

TEST(TransferFunction, InterpolationBetweenStopsPerSpace) {
    // Midpoint of black (0) -> red (2) at value 1.
    EXPECT_EQ(test::dn(threeStops(Space::Srgb).evaluate(1.0))[0], 128);
    EXPECT_NEAR(threeStops(Space::Linear).evaluate(1.0).r * 255.0, 187.5, 0.6);
    // Lab: black (L*0) and red (L*53.24, a*80.09, b*67.20) average to (26.62, 40.05, 33.60),
    // which converts back to sRGB (122.3, 26.8, 12.1) -- computed independently in Python.
    const auto lab = test::dn(threeStops(Space::Lab).evaluate(1.0));
    EXPECT_NEAR(lab[0], 122, 1);
    EXPECT_NEAR(lab[1], 27, 1);
    EXPECT_NEAR(lab[2], 12, 1);
}

TEST(TransferFunction, EqualStopValuesMakeAStep) {
    TransferFunction tf;
    tf.space = Space::Srgb;
    tf.stops = {{0, hex("#000000")}, {1, hex("#000000")}, {1, hex("#ffffff")}, {2, hex("#ffffff")}};
    ASSERT_FALSE(tf.finalize(false, false, false).hasErrors());
    EXPECT_EQ(test::dn(tf.evaluate(0.999))[0], 0);
    EXPECT_EQ(test::dn(tf.evaluate(1.0))[0], 255);
    EXPECT_EQ(test::dn(tf.evaluate(1.5))[0], 255);
}

TEST(TransferFunction, NodataBelowAboveAndOpacity) {
    TransferFunction tf = threeStops(Space::Srgb);
    tf.nodata = hex("#00ff00");
    tf.below = hex("#0000ff");
    tf.opacity = {{0.0, 0.0}, {1.0, 1.0}};
    ASSERT_FALSE(tf.finalize(false, true, false).hasErrors());
    EXPECT_EQ(tf.shade(std::numeric_limits<double>::quiet_NaN()), hex("#00ff00"));
    EXPECT_EQ(tf.shade(-1.0), hex("#0000ff"));      // explicit below kept
    EXPECT_EQ(tf.shade(9.0), hex("#ffffff"));       // derived above
    EXPECT_EQ(test::dn(tf.evaluate(0.5))[3], 128);  // half-way up the ramp
    EXPECT_EQ(test::dn(tf.evaluate(3.0))[3], 255);
    const auto lut = buildLut(tf);
    EXPECT_EQ(lut[3], 0);  // value 0 -> opacity 0
}

TEST(TransferFunction, ClassBreaksAndPatches) {
    TransferFunction tf;
    tf.units = "m";
    tf.classes = {
        {0.5, hex("#00ff00"), ""}, {0.0, hex("#ff0000"), "dry"}, {1.0, hex("#0000ff"), ""}};
    ASSERT_FALSE(tf.finalize(false, false, false).hasErrors());
    EXPECT_TRUE(tf.discrete());
    EXPECT_EQ(tf.domainMin, 0.0);
    EXPECT_EQ(tf.domainMax, 1.5);  // last class as wide as the one before
    EXPECT_EQ(tf.evaluate(0.7), hex("#00ff00"));
    EXPECT_EQ(tf.evaluate(0.5), hex("#00ff00"));  // lower bound inclusive
    EXPECT_EQ(tf.evaluate(0.49), hex("#ff0000"));
    EXPECT_EQ(tf.shade(-1), hex("#ff0000"));
    EXPECT_EQ(tf.shade(7), hex("#0000ff"));
    const auto lut = buildLut(tf, 1024);
    EXPECT_EQ(lut[4 * 1023 + 2], 255);  // last texel is blue
    EXPECT_EQ(lut[0], 255);             // first texel is red
    const auto patches = legendPatches(tf);
    ASSERT_EQ(patches.size(), 3u);
    EXPECT_EQ(patches[0].label, "dry");
    EXPECT_EQ(patches[1].label, "0.5 - 1 m");
    EXPECT_EQ(patches[2].label, "1 - 1.5 m");
    EXPECT_EQ(patches[2].color, hex("#0000ff"));
    EXPECT_TRUE(legendTicks(tf).empty());
}

TEST(TransferFunction, RescaledMapsStopsOntoNewDomain) {
    const TransferFunction tf = threeStops(Space::Srgb).rescaled(10, 20);
    EXPECT_EQ(tf.stops[1].value, 14.0);
    EXPECT_EQ(tf.domainMin, 10.0);
    EXPECT_EQ(tf.evaluate(14.0), hex("#ff0000"));
}

struct BadTf {
    const char* name;
    TransferFunction tf;
    const char* code;
    const char* message;
};

TEST(TransferFunction, BadDefinitionsReportCodes) {
    TransferFunction empty;
    empty.name = "e";
    TransferFunction single;
    single.name = "s";
    single.stops = {{1.0, hex("#000000")}};
    TransferFunction nan;
    nan.name = "n";
    nan.stops = {{0, hex("#000000")}, {std::numeric_limits<double>::infinity(), hex("#ffffff")}};
    const BadTf cases[] = {
        {"empty", empty, "TF_EMPTY", "transfer function \"e\" has no stops"},
        {"single stop", single, "TF_DOMAIN", "is empty"},
        {"infinite stop", nan, "TF_NOT_FINITE", "not finite"},
    };
    for (auto c : cases) {
        const Diagnostics d = c.tf.finalize(false, false, false, "f.json", "/tf");
        ASSERT_TRUE(d.hasErrors()) << c.name;
        EXPECT_EQ(d.firstError()->code, c.code) << c.name;
        EXPECT_NE(d.format().find(c.message), std::string::npos) << d.format();
        EXPECT_NE(d.format().find("f.json: /tf: "), std::string::npos) << d.format();
    }
}

TEST(Legend, NiceNumbersAndTicks) {
    EXPECT_EQ(niceNumber(0.23, true), 0.2);
    EXPECT_EQ(niceNumber(3.2, true), 5.0);
    EXPECT_EQ(niceNumber(32.6, false), 50.0);
    EXPECT_EQ(niceNumber(7.5, true), 10.0);

    TransferFunction tf = threeStops(Space::Lab);
    auto ticks = legendTicks(tf, 6);
    ASSERT_EQ(ticks.size(), 6u);
    EXPECT_EQ(ticks[0].label, "0");
    EXPECT_EQ(ticks[5].label, "5");
    EXPECT_DOUBLE_EQ(ticks[2].position, 0.4);

    tf = tf.rescaled(0, 1);
    ticks = legendTicks(tf, 6);
    ASSERT_EQ(ticks.size(), 6u);
    EXPECT_EQ(ticks[1].label, "0.2");
    EXPECT_EQ(ticks[0].label, "0.0");

    tf = tf.rescaled(-30.34, 2.29);
    ticks = legendTicks(tf, 6);
    ASSERT_EQ(ticks.size(), 4u);
    EXPECT_EQ(ticks[0].label, "-30");
    EXPECT_EQ(ticks[3].label, "0");
    EXPECT_NEAR(ticks[3].position, 30.34 / 32.63, 1e-9);
}

}  // namespace
}  // namespace kiosk::color
