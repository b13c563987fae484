#include "runtime/render/OverlayRenderer.h"

#include <gtest/gtest.h>

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
