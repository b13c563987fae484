#include "runtime/render/OverlayRenderer.h"

#include <gtest/gtest.h>

#include "runtime/color/TransferFunction.h"
#include "runtime/render/Textures.h"
#include "tests/support/EglTestContext.h"

namespace kiosk::render {
namespace {

class OverlayRendererGLTest : public test::EglTest {};

TEST_F(OverlayRendererGLTest, RectTextAndImageStrip) {
    auto rt = makeTarget(200, 100);
    auto overlay = OverlayRenderer::create(FontAtlas::defaultFontPath(), 20);
    ASSERT_TRUE(overlay.ok()) << overlay.diagnostics.format();
    const std::uint8_t lut[] = {255, 0, 0, 255, 0, 0, 255, 255};
    auto lutTex = makeLutTexture(2, lut);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    overlay->begin(200, 100);
    overlay->rect(10, 10, 20, 20, {0.0f, 1.0f, 0.0f, 1.0f});
    const float w = overlay->text(50, 40, "Flood 2.5 m", {1, 1, 1, 1});
    overlay->image(10, 60, 180, 20, lutTex.id());
    overlay->end();
    EXPECT_GL_OK();
    auto img = rt.readColor();
    // Solid rectangle: exact colour inside, untouched outside.
    EXPECT_EQ(img.pixel(20, 20)[1], 255);
    EXPECT_EQ(img.pixel(20, 20)[0], 0);
    EXPECT_EQ(img.pixel(35, 20)[1], 0);
    // Text: some white coverage between the pen start and its measured advance, above the baseline.
    EXPECT_GT(w, 80.0f);
    EXPECT_NEAR(w, overlay->measure("Flood 2.5 m"), 1e-3);
    int lit = 0;
    for (int y = 22; y < 42; ++y)
        for (int x = 50; x < 50 + int(w); ++x) lit += img.pixel(x, y)[0] > 128;
    EXPECT_GT(lit, 60);
    int outside = 0;
    for (int y = 22; y < 42; ++y)
        for (int x = 52 + int(w); x < 200; ++x) outside += img.pixel(x, y)[0] > 0;
    EXPECT_EQ(outside, 0);
    // LUT strip: red at the left end, blue at the right, a mix in the middle.
    EXPECT_GT(img.pixel(11, 70)[0], 240);
    EXPECT_GT(img.pixel(188, 70)[2], 240);
    EXPECT_NEAR(img.pixel(100, 70)[0], 128, 4);
}

// Issue 5: one definition drives both the shader LUT and the legend, so the legend bar's pixels
// are the transfer function's colours at the values the bar's ticks name.
TEST_F(OverlayRendererGLTest, LegendBarPixelsAreTheTransferFunctionColours) {
    constexpr int kW = 300, kH = 40, kBarX = 20, kBarW = 256;
    auto rt = makeTarget(kW, kH);
    auto overlay = OverlayRenderer::create(FontAtlas::defaultFontPath(), 14);
    ASSERT_TRUE(overlay.ok()) << overlay.diagnostics.format();
    color::TransferFunction tf;
    tf.space = color::Space::Lab;
    tf.stops = {{0.0, {0.83f, 0.96f, 0.98f, 1}}, {0.5, {0.42f, 0.68f, 0.84f, 1}},
                {2.0, {0.13f, 0.44f, 0.71f, 1}}, {5.0, {0.03f, 0.19f, 0.42f, 1}}};
    ASSERT_FALSE(tf.finalize(false, false, false).hasErrors());
    const auto lut = color::buildLut(tf, color::kMinLutSize);
    auto tex = makeLutTexture(int(lut.size() / 4), lut.data());
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    overlay->begin(kW, kH);
    overlay->image(float(kBarX), 10, float(kBarW), 20, tex.id());
    overlay->end();
    EXPECT_GL_OK();
    const auto img = rt.readColor();
    for (int i = 0; i < kBarW; i += 5) {
        const double t = (i + 0.5) / kBarW;
        const color::Rgba want = tf.evaluate(tf.domainMin + t * (tf.domainMax - tf.domainMin));
        const auto* p = img.pixel(kBarX + i, 20);
        // 2 DN: 8-bit LUT rounding plus linear filtering between neighbouring LUT texels.
        EXPECT_NEAR(p[0], want.r * 255.0f, 2.0f) << "at " << t;
        EXPECT_NEAR(p[1], want.g * 255.0f, 2.0f) << "at " << t;
        EXPECT_NEAR(p[2], want.b * 255.0f, 2.0f) << "at " << t;
    }
}

TEST_F(OverlayRendererGLTest, MissingFontIsReportedNotFatal) {
    auto overlay = OverlayRenderer::create("/nonexistent/font.ttf", 20);
    ASSERT_FALSE(overlay.ok());
    EXPECT_TRUE(overlay.diagnostics.has("FONT_LOAD"));
    EXPECT_NE(overlay.diagnostics.format().find("/nonexistent/font.ttf"), std::string::npos);
}

TEST(FontAtlasTest, Utf8ToLatin1) {
    EXPECT_EQ(utf8ToLatin1("T+6 h"), "T+6 h");
    EXPECT_EQ(utf8ToLatin1("\xC2\xB0" "C"), "\xB0" "C");  // degree sign
    EXPECT_EQ(utf8ToLatin1("\xE2\x86\x92"), "?");         // arrow: outside Latin-1
}

}  // namespace
}  // namespace kiosk::render
