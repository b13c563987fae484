#include "runtime/color/ColorSpace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace kiosk::color {
namespace {

int dn(double v) {
    return int(std::lround(v * 255.0));
}

TEST(ColorSpace, SrgbTransferIsTheIecCurve) {
    EXPECT_DOUBLE_EQ(srgbToLinear(0.0), 0.0);
    EXPECT_DOUBLE_EQ(srgbToLinear(1.0), 1.0);
    EXPECT_NEAR(srgbToLinear(0.5), 0.214041, 1e-6);        // ((0.5+0.055)/1.055)^2.4
    EXPECT_NEAR(srgbToLinear(0.04), 0.04 / 12.92, 1e-12);  // linear toe
    EXPECT_NEAR(linearToSrgb(0.214041), 0.5, 1e-6);
    EXPECT_DOUBLE_EQ(linearToSrgb(2.0), 1.0);  // clamped
}

TEST(ColorSpace, KnownLabValues) {
    const Vec3 white = toSpace({1, 1, 1}, Space::Lab);
    EXPECT_NEAR(white[0], 100.0, 1e-3);
    EXPECT_NEAR(white[1], 0.0, 1e-2);
    EXPECT_NEAR(white[2], 0.0, 1e-2);
    // sRGB red under D65: L* 53.24, a* 80.09, b* 67.20 (Lindbloom's calculator).
    const Vec3 red = toSpace({1, 0, 0}, Space::Lab);
    EXPECT_NEAR(red[0], 53.24, 0.02);
    EXPECT_NEAR(red[1], 80.09, 0.05);
    EXPECT_NEAR(red[2], 67.20, 0.05);
    const Vec3 black = toSpace({0, 0, 0}, Space::Lab);
    EXPECT_NEAR(black[0], 0.0, 1e-9);
}

TEST(ColorSpace, LabAndMshRoundTrips) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 c{u(rng), u(rng), u(rng)};
        for (Space s : {Space::Linear, Space::Lab, Space::Msh}) {
            const Vec3 back = fromSpace(toSpace(c, s), s);
            for (int k = 0; k < 3; ++k)
                ASSERT_NEAR(back[std::size_t(k)], c[std::size_t(k)], 1e-6)
                    << spaceName(s) << " colour " << i;
        }
    }
    // Msh of a grey has zero saturation; of a saturated colour, s > 0.
    EXPECT_NEAR(labToMsh(toSpace({0.5, 0.5, 0.5}, Space::Lab))[1], 0.0, 1e-3);
    EXPECT_GT(toSpace({0, 0, 1}, Space::Msh)[1], 0.5);
}

// Hand-computed midpoints of black -> white in each space.
TEST(ColorSpace, MidpointsPerSpace) {
    const Vec3 k{0, 0, 0}, w{1, 1, 1};
    EXPECT_EQ(dn(interpolate(k, w, 0.5, Space::Srgb)[0]), 128);  // 127.5 rounds up
    // linear 0.5 -> sRGB 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5
    EXPECT_NEAR(interpolate(k, w, 0.5, Space::Linear)[0] * 255.0, 187.5, 0.6);
    // L* 50 -> Y = (66/116)^3 = 0.18419 -> sRGB 0.46635 -> 118.9
    EXPECT_EQ(dn(interpolate(k, w, 0.5, Space::Lab)[1]), 119);
}

// Moreland's cool-to-warm map: the diverging midpoint is an unsaturated grey with
// M = max(M1, M2, 88), i.e. L* = 88 -> sRGB 220.7 in every channel.
TEST(ColorSpace, MshDivergingMidpointIsWhiteish) {
    const Vec3 cool{59 / 255.0, 76 / 255.0, 192 / 255.0}, warm{180 / 255.0, 4 / 255.0, 38 / 255.0};
    const Vec3 mid = interpolate(cool, warm, 0.5, Space::Msh);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(dn(mid[std::size_t(c)]), 221) << c;
    // Ends are reproduced exactly.
    const Vec3 a = interpolate(cool, warm, 0.0, Space::Msh);
    EXPECT_EQ(dn(a[2]), 192);
    const Vec3 b = interpolate(cool, warm, 1.0, Space::Msh);
    EXPECT_EQ(dn(b[0]), 180);
    // Lab would pass through a muddy purple instead: clearly different.
    EXPECT_LT(dn(interpolate(cool, warm, 0.5, Space::Lab)[1]), 120);
}

TEST(ColorSpace, ParseColor) {
    EXPECT_EQ(parseColor("#ff8000"), (Rgba{1.0f, 128 / 255.0f, 0.0f, 1.0f}));
    EXPECT_EQ(parseColor("#FF800080")->a, 128 / 255.0f);
    EXPECT_EQ(parseColor("#fff"), (Rgba{1, 1, 1, 1}));
    EXPECT_EQ(parseColor("Transparent"), (Rgba{0, 0, 0, 0}));
    EXPECT_EQ(parseColor("navy"), (Rgba{0, 0, 128 / 255.0f, 1}));
    for (const char* bad : {"", "#", "#12345", "#12345z", "reed", "#1234567", "rgb(1,2,3)"})
        EXPECT_FALSE(parseColor(bad).has_value()) << bad;
    EXPECT_EQ(formatColor(Rgba{1, 0, 0, 1}), "#ff0000ff");
}

TEST(ColorSpace, ParseSpace) {
    EXPECT_EQ(parseSpace("msh"), Space::Msh);
    EXPECT_EQ(parseSpace("lab"), Space::Lab);
    EXPECT_FALSE(parseSpace("hsv"));
    EXPECT_STREQ(spaceName(Space::Linear), "linear");
}

}  // namespace
}  // namespace kiosk::color
