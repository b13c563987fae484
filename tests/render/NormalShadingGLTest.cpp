// Normal-map layers lit at run time (issue 7): Lambert of the decoded normal map equals Lambert
// of the analytic normal within 2 DN; nodata stays transparent; the hybrid switch to geometry
// shading near the camera is continuous over distance and over the screen.
#include "runtime/render/NormalShading.h"
#include "runtime/render/TerrainRenderer.h"
#include "runtime/render/Textures.h"
#include "runtime/topo/NormalMap.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/MeshFixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace kiosk::render {
namespace {

constexpr double kTile = 1000.0;  // metres, the flat test tile [0, 1000]^2

class NormalShadingGLTest : public test::EglTest {
protected:
    void SetUp() override {
        test::EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        mMesh = GpuMesh::upload(test::gridMesh(3, 500.0, [](double, double) { return 0.0; }));
        auto r = TerrainRenderer::create({{{LayerKind::Normals, LayerOp::Modulate, -1}}, {}, 0});
        ASSERT_TRUE(r.ok()) << r.diagnostics.format();
        mRenderer.emplace(std::move(*r.value));
    }

    static math::Camera camera(double range, int size) {
        auto c = math::Camera::fromViewpoint({{500.0, 500.0, 0.0}, 0.0, -89.9, range}, size, size);
        c.fitClipPlanes({0, 0, -1}, {kTile, kTile, 1});
        return c;
    }

    /** Flat white tile modulated by the normal-map layer `tex`; the image read back. */
    gl::Image render(const math::Camera& cam, int size, const gl::Texture& tex,
                     const TerrainStyle& style) {
        auto target = makeTarget(size, size);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        mRenderer->begin(cam, glm::dvec3(0.0), style);
        LayerBinding b;
        b.texture = tex.id();
        b.west = 0;
        b.north = kTile;
        b.width = kTile;
        b.height = kTile;
        b.valid = true;
        mRenderer->setLayer(0, b);
        mRenderer->draw(mMesh, glm::dvec3(0.0));
        mRenderer->end();
        EXPECT_GL_OK();
        return target.readColor();
    }

    static TerrainStyle style(glm::vec3 light, float ambient, float tauTex,
                              glm::vec3 base = glm::vec3(1.0f)) {
        TerrainStyle s;
        s.geometryLighting = 0.0f;
        s.elevationLutWeight = 0.0f;
        s.baseColor = glm::vec4(base, 1.0f);
        s.lightDir = light;
        s.ambient = ambient;
        s.tauTex = tauTex;
        return s;
    }

    /** Ground point (z = 0) under the centre of pixel (px, py), image rows top first. */
    static glm::dvec2 ground(const math::Camera& cam, int size, int px, int py) {
        const glm::dmat4 inv = glm::inverse(cam.projection() * cam.view());
        const double x = (px + 0.5) / size * 2.0 - 1.0, y = 1.0 - (py + 0.5) / size * 2.0;
        glm::dvec4 a = inv * glm::dvec4(x, y, -1.0, 1.0), b = inv * glm::dvec4(x, y, 1.0, 1.0);
        const glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
        const double t = p0.z / (p0.z - p1.z);
        return glm::dvec2(p0 + t * (p1 - p0));
    }

    /** A texture of one encoded normal everywhere, or nodata (all zero) left of `nodataBelowX`. */
    static gl::Texture constantNormal(int n, glm::dvec3 normal, int nodataBelowX = 0) {
        std::vector<std::uint8_t> rgba(std::size_t(n) * std::size_t(n) * 4, 0);
        std::uint8_t t[3];
        topo::encodeNormal({normal.x, normal.y, normal.z}, topo::NormalEncoding::Rgb8, t);
        for (int y = 0; y < n; ++y)
            for (int x = nodataBelowX; x < n; ++x) {
                std::uint8_t* p = &rgba[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 4];
                p[0] = t[0], p[1] = t[1], p[2] = t[2], p[3] = 255;
            }
        return makeRgbaTexture(n, n, rgba.data(), true);
    }

    GpuMesh mMesh;
    std::optional<TerrainRenderer> mRenderer;
};

// A Gaussian hill: 300 m high, sigma 200 m, centred on the tile (slopes up to 0.9).
double hill(double x, double y) {
    const double dx = x - 500.0, dy = y - 500.0;
    return 300.0 * std::exp(-(dx * dx + dy * dy) / (2.0 * 200.0 * 200.0));
}
glm::dvec3 hillNormal(double x, double y) {
    const double h = hill(x, y), dx = x - 500.0, dy = y - 500.0;
    const double gx = -h * dx / (200.0 * 200.0), gy = -h * dy / (200.0 * 200.0);
    return glm::normalize(glm::dvec3(-gx, -gy, 1.0));
}

TEST_F(NormalShadingGLTest, LambertOfNormalMapEqualsLambertOfAnalyticNormal) {
    // The importer's path: topo::normalMap of the full-resolution DEM (texel centres, with a
    // one-texel apron), Rgb8 in RGB, validity in A, uploaded with mipmaps like a store tile.
    constexpr int kTex = 128, kPx = 128;
    const double texel = kTile / kTex;
    std::vector<float> dem(std::size_t(kTex + 2) * std::size_t(kTex + 2));
    for (int r = 0; r < kTex + 2; ++r)
        for (int c = 0; c < kTex + 2; ++c)  // row 0 of the window is the north edge
            dem[std::size_t(r) * (kTex + 2) + std::size_t(c)] =
                float(hill((c - 0.5) * texel, kTile - (r - 0.5) * texel));
    topo::RasterView v = topo::RasterView::window(dem.data(), kTex + 2, kTex + 2, kTex + 2, 1, 1,
                                                  kTex, kTex, texel, texel);
    std::vector<std::uint8_t> rgb(std::size_t(kTex) * kTex * 3), rgba(std::size_t(kTex) * kTex * 4);
    ASSERT_FALSE(topo::normalMap(v, {}, rgb.data(), kTex * 3).hasErrors());
    for (std::size_t i = 0; i < std::size_t(kTex) * kTex; ++i) {
        for (int k = 0; k < 3; ++k) rgba[i * 4 + std::size_t(k)] = rgb[i * 3 + std::size_t(k)];
        rgba[i * 4 + 3] = 255;
    }
    auto tex = makeRgbaTexture(kTex, kTex, rgba.data(), true);
    // 7.4 m pixels on 7.8 m texels: magnified, so mip level 0 (as a tile at its own level).
    const auto cam = camera(1150.0, kPx);
    struct Light {
        double az, alt;
        float ambient;
    };
    for (const Light l : {Light{315, 45, 0.0f}, Light{100, 20, 0.25f}, Light{200, 60, 0.3f}}) {
        const glm::vec3 sun = sunDirection(l.az, l.alt);
        // tauTex 4: texels (7.8 m) cover ~1 pixel here, so this is texture shading only.
        auto img = render(cam, kPx, tex, style(sun, l.ambient, 4.0f));
        int worst = 0, compared = 0;
        for (int py = 4; py < kPx - 4; ++py)
            for (int px = 4; px < kPx - 4; ++px) {
                const glm::dvec2 g = ground(cam, kPx, px, py);
                if (g.x < 10 || g.y < 10 || g.x > kTile - 10 || g.y > kTile - 10) continue;
                const double lam = std::max(glm::dot(hillNormal(g.x, g.y), glm::dvec3(sun)), 0.0);
                const int want = int(std::lround(255.0 * (l.ambient + (1.0 - l.ambient) * lam)));
                const int diff = std::abs(int(img.pixel(px, py)[0]) - want);
                worst = std::max(worst, diff);
                ++compared;
            }
        EXPECT_GT(compared, 100 * 100);
        EXPECT_LE(worst, 2) << "sun " << l.az << "/" << l.alt;
    }
    // Control: the same comparison with the light rotated by 10 degrees must fail.
    const glm::vec3 sun = sunDirection(315, 45);
    auto img = render(cam, kPx, tex, style(sunDirection(325, 45), 0.0f, 4.0f));
    int worst = 0;
    for (int py = 8; py < kPx - 8; ++py)
        for (int px = 8; px < kPx - 8; ++px) {
            const glm::dvec2 g = ground(cam, kPx, px, py);
            const double lam = std::max(glm::dot(hillNormal(g.x, g.y), glm::dvec3(sun)), 0.0);
            worst = std::max(worst,
                             std::abs(int(img.pixel(px, py)[0]) - int(std::lround(255.0 * lam))));
        }
    EXPECT_GT(worst, 10);
}

TEST_F(NormalShadingGLTest, VerticalExaggerationSteepensDecodedNormals) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, 0.0, 1.0));
    auto tex = constantNormal(16, n);
    const auto cam = camera(1300.0, 16);
    const glm::vec3 up(0, 0, 1);
    TerrainStyle s = style(up, 0.0f, 4.0f);
    s.verticalScale = 3.0f;
    const int got = render(cam, 16, tex, s).pixel(8, 8)[0];
    const double want = 255.0 / std::sqrt(0.9 * 0.9 + 1.0);  // n.xy scaled by 3
    EXPECT_NEAR(got, want, 2.0);
}

TEST_F(NormalShadingGLTest, NodataStaysTransparentWithoutARim) {
    // Left quarter of the texture is nodata; the rest a tilted normal lit at 0.5.
    constexpr int kTex = 32, kPx = 64;
    const glm::dvec3 n = glm::normalize(glm::dvec3(std::sqrt(3.0), 0.0, 1.0));  // 60 deg tilt
    auto tex = constantNormal(kTex, n, kTex / 4);
    const auto cam = camera(1300.0, kPx);
    const glm::vec3 base(0.8f, 0.6f, 0.4f);
    auto img = render(cam, kPx, tex, style(glm::vec3(0, 0, 1), 0.0f, 100.0f, base));
    const int lit = int(std::lround(255.0 * 0.8 * n.z));  // red channel of the shaded base
    const int plain = int(std::lround(255.0 * 0.8));
    bool sawNodata = false, sawLit = false;
    for (int px = 0; px < kPx; ++px) {
        const glm::dvec2 g = ground(cam, kPx, px, kPx / 2);
        if (g.x < 1 || g.x > kTile - 1) continue;
        const int r = img.pixel(px, kPx / 2)[0];
        // Between the unshaded base and the shaded value: no darker or brighter rim.
        EXPECT_GE(r, lit - 1) << "x " << g.x;
        EXPECT_LE(r, plain + 1) << "x " << g.x;
        if (g.x < kTile / 4 - 40) {
            EXPECT_NEAR(r, plain, 1) << "nodata must leave the layers below unchanged, x " << g.x;
            sawNodata = true;
        }
        if (g.x > kTile / 4 + 40) {
            EXPECT_NEAR(r, lit, 1) << "x " << g.x;
            sawLit = true;
        }
    }
    EXPECT_TRUE(sawNodata && sawLit);
}

TEST_F(NormalShadingGLTest, HybridBlendIsContinuousFromTextureFarToGeometryNear) {
    // Flat mesh (geometry normal up) with a normal map tilted by 36.9 degrees, sun overhead:
    // texture shading 0.8 (204 DN), geometry shading 1.0 (255 DN). Texels are 1000/64 m.
    constexpr int kTex = 64, kPx = 64;
    auto tex = constantNormal(kTex, glm::normalize(glm::dvec3(0.6, 0.0, 0.8)));
    const TerrainStyle s = style(glm::vec3(0, 0, 1), 0.0f, 1.0f);
    std::vector<int> centre;
    std::vector<double> ranges;
    for (double range = 4000.0; range > 150.0; range *= 0.97) ranges.push_back(range);
    int maxRowStep = 0;
    for (double range : ranges) {
        const auto cam = camera(range, kPx);
        auto img = render(cam, kPx, tex, s);
        centre.push_back(img.pixel(kPx / 2, kPx / 2)[0]);
        for (int px = 1; px < kPx; ++px)  // no seam across the screen either
            if (glm::abs(ground(cam, kPx, px - 1, kPx / 2).x - 500.0) < 480.0 &&
                glm::abs(ground(cam, kPx, px, kPx / 2).x - 500.0) < 480.0)
                maxRowStep = std::max(maxRowStep, std::abs(int(img.pixel(px, kPx / 2)[0]) -
                                                           int(img.pixel(px - 1, kPx / 2)[0])));
        // The rule, checked on the pixel: weight from screen pixels per texel at the centre.
        const double ppt = (kTile / kTex) * cam.pixelsPerMetreAt(range);
        const double want = 204.0 + 51.0 * hybridGeometryWeight(float(ppt), 1.0f);
        EXPECT_NEAR(centre.back(), want, 3.0) << "range " << range << " px/texel " << ppt;
    }
    EXPECT_NEAR(centre.front(), 204, 1) << "far: texture shading";
    EXPECT_NEAR(centre.back(), 255, 1) << "near: geometry shading";
    int maxStep = 0;
    for (std::size_t i = 1; i < centre.size(); ++i)
        maxStep = std::max(maxStep, std::abs(centre[i] - centre[i - 1]));
    EXPECT_LE(maxStep, 4) << "a visible jump between adjacent distances";
    EXPECT_LE(maxRowStep, 2);
}

TEST(NormalShadingRule, HybridWeight) {
    EXPECT_EQ(hybridGeometryWeight(0.5f, 1.0f), 0.0f);
    EXPECT_EQ(hybridGeometryWeight(1.0f, 1.0f), 0.0f);
    EXPECT_NEAR(hybridGeometryWeight(std::sqrt(2.0f), 1.0f), 0.5f, 1e-6f);
    EXPECT_EQ(hybridGeometryWeight(2.0f, 1.0f), 1.0f);
    EXPECT_EQ(hybridGeometryWeight(8.0f, 2.0f), 1.0f);
    EXPECT_EQ(hybridGeometryWeight(3.0f, 0.0f), 0.0f);
    EXPECT_EQ(hybridGeometryWeight(NAN, 1.0f), 0.0f);
}

}  // namespace
}  // namespace kiosk::render
