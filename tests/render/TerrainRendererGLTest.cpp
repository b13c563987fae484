#include "runtime/render/TerrainRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "runtime/render/FillBound.h"
#include "runtime/render/OverlayRenderer.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/GoldenImage.h"
#include "tests/support/MeshFixtures.h"

namespace kiosk::render {
namespace {

class TerrainRendererGLTest : public test::EglTest {};

math::Camera topDown(glm::dvec3 target, double range, int w, int h) {
    // Pitch -89.9 keeps "up" well defined; the image is north-up.
    return math::Camera::fromViewpoint({target, 0.0, -89.9, range}, w, h);
}

TEST_F(TerrainRendererGLTest, FlatPlaneShowsLutColourAtItsElevation) {
    auto rt = makeTarget(64, 64);
    auto renderer = TerrainRenderer::create();
    ASSERT_TRUE(renderer.ok()) << renderer.diagnostics.format();
    // Three-stop LUT over 0..200 m: at 100 m the centre texel is exactly (10, 200, 30).
    const std::uint8_t lut[] = {255, 0, 0, 255, 10, 200, 30, 255, 0, 0, 255, 255};
    renderer->setElevationLut(3, lut, 0.0f, 200.0f);
    auto mesh = GpuMesh::upload(test::gridMesh(5, 250.0, [](double, double) { return 100.0; }));
    auto cam = topDown({500.0, 500.0, 100.0}, 800.0, 64, 64);
    cam.fitClipPlanes({0, 0, 0}, {1000, 1000, 200});
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    TerrainStyle style;
    style.lightDir = {0, 0, 1};  // sun overhead: a flat surface gets full light
    style.ambient = 0.2f;
    renderer->begin(cam, glm::dvec3(0.0), style);
    renderer->draw(mesh, glm::dvec3(0.0));
    renderer->end();
    EXPECT_GL_OK();
    auto img = rt.readColor();
    const auto* px = img.pixel(32, 32);
    EXPECT_NEAR(px[0], 10, 1);
    EXPECT_NEAR(px[1], 200, 1);
    EXPECT_NEAR(px[2], 30, 1);
    EXPECT_EQ(renderer->counters().tilesDrawn, 1u);
    EXPECT_EQ(renderer->counters().triangles, 32u);
}

TEST_F(TerrainRendererGLTest, HillIsLitOnTheSunSideAndMatchesGolden) {
    auto rt = makeTarget(160, 120);
    auto renderer = TerrainRenderer::create();
    ASSERT_TRUE(renderer.ok()) << renderer.diagnostics.format();
    const std::uint8_t lut[] = {60, 120, 60, 255, 200, 190, 170, 255};
    renderer->setElevationLut(2, lut, 0.0f, 400.0f);
    auto hill = [](double x, double y) {
        const double dx = x - 1000.0, dy = y - 1000.0;
        return 400.0 * std::exp(-(dx * dx + dy * dy) / (2.0 * 300.0 * 300.0));
    };
    auto mesh = GpuMesh::upload(test::gridMesh(65, 2000.0 / 64.0, hill));
    auto cam = topDown({1000.0, 1000.0, 0.0}, 2600.0, 160, 120);
    cam.fitClipPlanes({0, 0, 0}, {2000, 2000, 400});
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    TerrainStyle style;
    style.lightDir = sunDirection(270.0, 30.0);  // sun in the west, low
    style.ambient = 0.1f;
    renderer->begin(cam, glm::dvec3(0.0), style);
    renderer->draw(mesh, glm::dvec3(0.0));
    renderer->end();
    EXPECT_GL_OK();
    auto img = rt.readColor();
    // Image is north-up: the west flank (left of centre) faces the sun, the east flank does not.
    const int west = img.pixel(80 - 18, 60)[0], east = img.pixel(80 + 18, 60)[0];
    EXPECT_GT(west, east + 40) << "west " << west << " east " << east;
    // llvmpipe is deterministic for a given Mesa build; 2 DN covers rounding differences
    // between Mesa point releases.
    EXPECT_EQ(test::compareWithGolden(img, "terrain_hill_west_sun", {2, 0.2}), "");
}

TEST_F(TerrainRendererGLTest, BrokenShaderOverrideFailsWithShaderNameAndKeepsRunning) {
    const auto dir = std::filesystem::temp_directory_path() / "kiosk-broken-shader";
    std::filesystem::create_directories(dir);
    {
        std::ofstream f(dir / "overlay.frag");
        f << "#version 300 es\nprecision highp float;\nout vec4 c;\nvoid main() { c = nope; }\n";
    }
    setenv("GEOKIOSK_SHADER_DIR", dir.c_str(), 1);
    auto renderer = OverlayRenderer::create(FontAtlas::defaultFontPath(), 16);
    unsetenv("GEOKIOSK_SHADER_DIR");
    ASSERT_FALSE(renderer.ok());
    EXPECT_TRUE(renderer.diagnostics.has("SHADER_COMPILE"));
    EXPECT_NE(renderer.diagnostics.format().find("overlay.frag:4"), std::string::npos)
        << renderer.diagnostics.format();
    // The embedded shader still builds afterwards.
    EXPECT_TRUE(TerrainRenderer::create().ok());
}

TEST_F(TerrainRendererGLTest, FillBoundDrawsEveryPixel) {
    auto rt = makeTarget(32, 32);
    auto fill = FillBound::create(4);
    ASSERT_TRUE(fill.ok()) << fill.diagnostics.format();
    glClearColor(1, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    fill->draw();
    EXPECT_GL_OK();
    auto img = rt.readColor();
    int magenta = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const auto* p = img.pixel(x, y);
            magenta += (p[0] == 255 && p[1] == 0 && p[2] == 255);
        }
    EXPECT_EQ(magenta, 0);
}

}  // namespace
}  // namespace kiosk::render
