#include "runtime/export/Yuv420.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

using kiosk::video::rgbaToYuv420Bt709;
using kiosk::video::Yuv420Planes;

namespace {

// The BT.709 limited-range definition (ITU-R BT.709-6 item 3.2-3.5, 8-bit quantisation) in
// doubles, independent of the fixed-point code under test.
struct Ycc {
    double y, cb, cr;
};
Ycc reference(double r, double g, double b) {
    const double kr = 0.2126, kb = 0.0722, kg = 1 - kr - kb;
    const double e = (kr * r + kg * g + kb * b) / 255.0;
    return {16 + 219 * e, 128 + 224 * ((b / 255.0 - e) / (2 * (1 - kb))),
            128 + 224 * ((r / 255.0 - e) / (2 * (1 - kr)))};
}

struct Picture {
    int w, h, pad;
    std::vector<std::uint8_t> y, u, v;
    Picture(int width, int height, int padding)
        : w(width),
          h(height),
          pad(padding),
          y(std::size_t((w + pad) * h), 0xAB),
          u(std::size_t((w / 2 + pad) * (h / 2)), 0xAB),
          v(u) {}
    Yuv420Planes planes() {
        return {y.data(), u.data(), v.data(), w + pad, w / 2 + pad, w / 2 + pad};
    }
    int Y(int x, int row) const { return y[std::size_t(row * (w + pad) + x)]; }
    int U(int x, int row) const { return u[std::size_t(row * (w / 2 + pad) + x)]; }
    int V(int x, int row) const { return v[std::size_t(row * (w / 2 + pad) + x)]; }
};

std::vector<std::uint8_t> solid(int w, int h, std::array<std::uint8_t, 3> c) {
    std::vector<std::uint8_t> px(std::size_t(w * h * 4));
    for (std::size_t i = 0; i < px.size(); i += 4) {
        px[i] = c[0];
        px[i + 1] = c[1];
        px[i + 2] = c[2];
        px[i + 3] = 255;
    }
    return px;
}

}  // namespace

TEST(Yuv420Test, PrimariesAndGreysHaveTheirBt709LimitedCodes) {
    struct Case {
        std::array<std::uint8_t, 3> rgb;
        int y, cb, cr;
    };
    // Codes of BT.709-6 (8-bit, narrow range) rounded to nearest.
    const Case cases[] = {{{0, 0, 0}, 16, 128, 128},        {{255, 255, 255}, 235, 128, 128},
                          {{128, 128, 128}, 126, 128, 128}, {{255, 0, 0}, 63, 102, 240},
                          {{0, 255, 0}, 173, 42, 26},       {{0, 0, 255}, 32, 240, 118},
                          {{255, 255, 0}, 219, 16, 138}};
    for (const Case& c : cases) {
        Picture p(4, 2, 0);
        const std::vector<std::uint8_t> px = solid(4, 2, c.rgb);
        rgbaToYuv420Bt709(px.data(), 4, 2, p.planes());
        SCOPED_TRACE(testing::Message()
                     << int(c.rgb[0]) << "," << int(c.rgb[1]) << "," << int(c.rgb[2]));
        EXPECT_EQ(p.Y(3, 1), c.y);
        EXPECT_EQ(p.U(1, 0), c.cb);
        EXPECT_EQ(p.V(1, 0), c.cr);
    }
}

TEST(Yuv420Test, RandomPixelsWithinHalfAStepOfTheFormula) {
    const int w = 64, h = 32;
    std::mt19937 rng(7);
    std::vector<std::uint8_t> px(std::size_t(w * h * 4));
    for (std::uint8_t& b : px) b = std::uint8_t(rng() & 0xFF);
    Picture p(w, h, 0);
    rgbaToYuv420Bt709(px.data(), w, h, p.planes());
    double worstY = 0, worstC = 0;
    for (int row = 0; row < h; ++row) {
        // The source is bottom row first: output row `row` is source row h-1-row.
        const std::uint8_t* s = px.data() + std::size_t((h - 1 - row) * w * 4);
        for (int x = 0; x < w; ++x) {
            const Ycc e = reference(s[4 * x], s[4 * x + 1], s[4 * x + 2]);
            worstY = std::max(worstY, std::abs(p.Y(x, row) - e.y));
        }
    }
    for (int row = 0; row < h / 2; ++row)
        for (int x = 0; x < w / 2; ++x) {
            double r = 0, g = 0, b = 0;
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx) {
                    const std::uint8_t* s =
                        px.data() + std::size_t(((h - 1 - (2 * row + dy)) * w + 2 * x + dx) * 4);
                    r += s[0] / 4.0;
                    g += s[1] / 4.0;
                    b += s[2] / 4.0;
                }
            const Ycc e = reference(r, g, b);
            worstC = std::max({worstC, std::abs(p.U(x, row) - e.cb), std::abs(p.V(x, row) - e.cr)});
        }
    // Rounding to nearest leaves at most half a code; the 16-bit weights add < 0.01.
    EXPECT_LE(worstY, 0.51);
    EXPECT_LE(worstC, 0.51);
}

TEST(Yuv420Test, TopOutputRowIsTheLastSourceRowAndPaddingIsUntouched) {
    const int w = 6, h = 4;
    std::vector<std::uint8_t> px = solid(w, h, {0, 0, 0});
    for (int x = 0; x < w; ++x) px[std::size_t((h - 1) * w + x) * 4] = 255;  // last row red
    Picture p(w, h, 3);
    rgbaToYuv420Bt709(px.data(), w, h, p.planes());
    for (int x = 0; x < w; ++x) {
        EXPECT_EQ(p.Y(x, 0), 63) << x;  // red on top
        for (int row = 1; row < h; ++row) EXPECT_EQ(p.Y(x, row), 16) << x << "," << row;
    }
    EXPECT_EQ(p.V(0, 0), (240 + 128 + 1) / 2);  // half red, half black in the top chroma row
    for (int row = 0; row < h; ++row)
        for (int x = w; x < w + 3; ++x) EXPECT_EQ(p.Y(x, row), 0xAB) << "padding written";
    for (int row = 0; row < h / 2; ++row)
        for (int x = w / 2; x < w / 2 + 3; ++x) {
            EXPECT_EQ(p.U(x, row), 0xAB);
            EXPECT_EQ(p.V(x, row), 0xAB);
        }
}
