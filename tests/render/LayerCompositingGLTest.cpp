// Each layer operation on known inputs gives the expected pixel within 1 DN (issue 5), and a
// sequence layer interpolates DATA values before the LUT (issue 6).
#include <gtest/gtest.h>

#include <cmath>

#include "runtime/anim/ArrivalThresholds.h"
#include "runtime/render/Textures.h"
#include "runtime/render/TerrainRenderer.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/MeshFixtures.h"
#include "tests/support/PixelAssert.h"

namespace kiosk::render {
namespace {

using test::dn;

constexpr int kSize = 32;
const glm::vec3 kBase(0.2f, 0.4f, 0.6f);

class LayerCompositingGLTest : public test::EglTest {
protected:
    void SetUp() override {
        test::EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        mTarget = std::make_unique<gl::RenderTarget>(makeTarget(kSize, kSize));
        mMesh = GpuMesh::upload(test::gridMesh(3, 500.0, [](double, double) { return 0.0; }));
        mCamera = math::Camera::fromViewpoint({{500.0, 500.0, 0.0}, 0.0, -89.9, 600.0}, kSize, kSize);
        mCamera.fitClipPlanes({0, 0, -1}, {1000, 1000, 1});
    }

    /** Render the flat 1 km tile with the stack; returns the centre pixel. */
    glm::ivec3 render(TerrainRenderer& r, const std::vector<LayerBinding>& layers,
                      int px = kSize / 2, int py = kSize / 2) {
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        TerrainStyle style;
        style.geometryLighting = 0.0f;
        style.elevationLutWeight = 0.0f;
        style.baseColor = glm::vec4(kBase, 1.0f);
        r.begin(mCamera, glm::dvec3(0.0), style);
        for (int i = 0; i < int(layers.size()); ++i) r.setLayer(i, layers[std::size_t(i)]);
        r.draw(mMesh, glm::dvec3(0.0));
        r.end();
        EXPECT_GL_OK();
        auto img = mTarget->readColor();
        const auto* p = img.pixel(px, py);
        return {p[0], p[1], p[2]};
    }

    static LayerBinding bind(const gl::Texture& t, float strength = 1.0f) {
        LayerBinding b;
        b.texture = t.id();
        b.west = 0;
        b.north = 1000;
        b.width = 1000;
        b.height = 1000;
        b.strength = strength;
        b.valid = true;
        return b;
    }

    static gl::Texture solid(glm::vec4 c) {
        std::uint8_t px[16];
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 4; ++k) px[i * 4 + k] = std::uint8_t(std::lround(c[k] * 255.0f));
        return makeRgbaTexture(2, 2, px, false);
    }

    std::unique_ptr<gl::RenderTarget> mTarget;
    GpuMesh mMesh;
    math::Camera mCamera;
};

TEST_F(LayerCompositingGLTest, BaseColourOnly) {
    auto r = TerrainRenderer::create();
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_DN_NEAR(render(*r, {}), dn(kBase));
}

TEST_F(LayerCompositingGLTest, OverWithOpacity) {
    auto r = TerrainRenderer::create({{{LayerKind::Thematic, LayerOp::Over, -1}}, {}, 0});
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    auto red = solid({1, 0, 0, 1});
    EXPECT_DN_NEAR(render(*r, {bind(red, 0.5f)}), dn(glm::mix(kBase, glm::vec3(1, 0, 0), 0.5f)));
}

TEST_F(LayerCompositingGLTest, WeightedAdd) {
    auto r = TerrainRenderer::create({{{LayerKind::Thematic, LayerOp::Add, -1}}, {}, 0});
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    auto grey = solid({0.4f, 0.4f, 0.4f, 1});
    EXPECT_DN_NEAR(render(*r, {bind(grey, 0.5f)}), dn(kBase + glm::vec3(0.2f)));
}

TEST_F(LayerCompositingGLTest, ModulateByTopographicShading) {
    auto r = TerrainRenderer::create({{{LayerKind::Topographic, LayerOp::Modulate, -1}}, {}, 0});
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const std::uint8_t shade[4] = {128, 128, 128, 128};
    auto t = makeR8Texture(2, 2, shade);
    EXPECT_DN_NEAR(render(*r, {bind(t)}), dn(kBase * (128.0f / 255.0f)));
}

TEST_F(LayerCompositingGLTest, BlendByVisibilityLayerAndChaining) {
    // Layer 0: visibility 25 %; layer 1: red blended by it; layer 2: modulate by 0.5 grey.
    CompositeProgramDesc desc{{{LayerKind::Visibility, LayerOp::Over, -1},
                               {LayerKind::Thematic, LayerOp::Blend, 0},
                               {LayerKind::Thematic, LayerOp::Modulate, -1}},
                              {},
                              0};
    auto r = TerrainRenderer::create(desc);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const std::uint8_t vis[4] = {64, 64, 64, 64};
    auto v = makeR8Texture(2, 2, vis);
    auto red = solid({1, 0, 0, 1});
    auto grey = solid({0.5f, 0.5f, 0.5f, 1});
    const glm::vec3 blended = glm::mix(kBase, glm::vec3(1, 0, 0), 64.0f / 255.0f);
    const glm::vec3 expected = blended * (128.0f / 255.0f);
    EXPECT_DN_NEAR(render(*r, {bind(v), bind(red), bind(grey)}), dn(expected));
}

TEST_F(LayerCompositingGLTest, MaskRevealsBackground) {
    CompositeProgramDesc desc{{{LayerKind::Thematic, LayerOp::Over, -1},
                               {LayerKind::Visibility, LayerOp::Mask, -1}},
                              {},
                              0};
    auto r = TerrainRenderer::create(desc);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    auto red = solid({1, 0, 0, 1});
    const std::uint8_t maskOff[4] = {0, 0, 0, 0}, maskOn[4] = {255, 255, 255, 255};
    auto off = makeR8Texture(2, 2, maskOff), on = makeR8Texture(2, 2, maskOn);
    EXPECT_DN_NEAR(render(*r, {bind(red), bind(off)}), dn(kBase));
    EXPECT_DN_NEAR(render(*r, {bind(red), bind(on)}), glm::ivec3(255, 0, 0));
}

class DataLayerGLTest : public LayerCompositingGLTest {
protected:
    // Four-stop LUT of 1024 entries over 0..4 m: value v maps to red = v/4, blue = 1 - v/4.
    void makeLut() {
        std::vector<std::uint8_t> lut(1024 * 4);
        for (int i = 0; i < 1024; ++i) {
            const float t = float(i) / 1023.0f;
            lut[std::size_t(i) * 4 + 0] = std::uint8_t(std::lround(t * 255.0f));
            lut[std::size_t(i) * 4 + 1] = 0;
            lut[std::size_t(i) * 4 + 2] = std::uint8_t(std::lround((1.0f - t) * 255.0f));
            lut[std::size_t(i) * 4 + 3] = 255;
        }
        mRamp = lut;
        mLutBinding.nodata = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
        mLut = makeEdgedLutTexture(1024, lut.data(), mLutBinding.below, mLutBinding.above,
                                   mLutBinding.nodata);
        mLutBinding.texture = mLut.id();
        mLutBinding.size = 1024;
        mLutBinding.domainMin = 0.0f;
        mLutBinding.domainMax = 4.0f;
    }
    static glm::ivec3 lutDn(float v) {
        const float t = std::clamp(v / 4.0f, 0.0f, 1.0f);
        return dn(glm::vec3(t, 0.0f, 1.0f - t));
    }
    std::vector<std::uint8_t> mRamp;
    gl::Texture mLut;
    LutBinding mLutBinding;
};

TEST_F(DataLayerGLTest, LutAtValuesAndNodataColour) {
    auto r = TerrainRenderer::create({{{LayerKind::Data, LayerOp::Over, -1}}, {}, 1});
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    makeLut();
    r->setLut(0, mLutBinding);
    for (float v : {0.0f, 1.0f, 2.5f, 4.0f}) {
        const float values[4] = {v, v, v, v};
        auto t = makeScalarTexture(2, 2, values, std::nullopt);
        EXPECT_DN_NEAR(render(*r, {bind(t)}), lutDn(v));
    }
    const float nan = std::nanf("");
    const float none[4] = {nan, nan, nan, nan};
    auto t = makeScalarTexture(2, 2, none, std::nullopt);
    EXPECT_DN_NEAR(render(*r, {bind(t)}), glm::ivec3(0, 255, 0));
    // nodataAs 0 (dry land counts as depth 0): the LUT's 0 colour instead of the nodata colour.
    auto dry = makeScalarTexture(2, 2, none, 0.0f);
    EXPECT_DN_NEAR(render(*r, {bind(dry)}), lutDn(0.0f));
}

TEST_F(DataLayerGLTest, BelowAndAboveColours) {
    auto r = TerrainRenderer::create({{{LayerKind::Data, LayerOp::Over, -1}}, {}, 1});
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    makeLut();
    mLutBinding.below = glm::vec4(1, 1, 0, 1);
    mLutBinding.above = glm::vec4(1, 1, 1, 1);
    mLut = makeEdgedLutTexture(1024, mRamp.data(), mLutBinding.below, mLutBinding.above,
                               mLutBinding.nodata);
    mLutBinding.texture = mLut.id();
    r->setLut(0, mLutBinding);
    const float lo[4] = {-1, -1, -1, -1}, hi[4] = {9, 9, 9, 9};
    auto tl = makeScalarTexture(2, 2, lo, std::nullopt), th = makeScalarTexture(2, 2, hi, std::nullopt);
    EXPECT_DN_NEAR(render(*r, {bind(tl)}), glm::ivec3(255, 255, 0));
    EXPECT_DN_NEAR(render(*r, {bind(th)}), glm::ivec3(255, 255, 255));
}

TEST_F(DataLayerGLTest, SequenceInterpolatesDataBeforeTheLut) {
    auto r = TerrainRenderer::create({{{LayerKind::Sequence, LayerOp::Over, -1}}, {}, 1});
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    // A LUT that is NOT linear in the value: a blend of two colours would differ from
    // LUT(mix(v0, v1)). Stops: 0 m blue, 0.4 m green, 0.8 m red (piecewise linear).
    std::vector<std::uint8_t> lut(1024 * 4);
    auto colourAt = [](float v) {
        const glm::vec3 blue(0, 0, 1), green(0, 1, 0), red(1, 0, 0);
        return v <= 0.4f ? glm::mix(blue, green, v / 0.4f) : glm::mix(green, red, (v - 0.4f) / 0.4f);
    };
    for (int i = 0; i < 1024; ++i) {
        const glm::vec3 c = colourAt(0.8f * float(i) / 1023.0f);
        for (int k = 0; k < 3; ++k) lut[std::size_t(i) * 4 + std::size_t(k)] = std::uint8_t(std::lround(c[k] * 255.0f));
        lut[std::size_t(i) * 4 + 3] = 255;
    }
    LutBinding lb;
    auto lutTex = makeEdgedLutTexture(1024, lut.data(), lb.below, lb.above, lb.nodata);
    lb.texture = lutTex.id();
    lb.size = 1024;
    lb.domainMin = 0.0f;
    lb.domainMax = 0.8f;
    r->setLut(0, lb);
    const float a[4] = {0.2f, 0.2f, 0.2f, 0.2f}, b[4] = {0.6f, 0.6f, 0.6f, 0.6f};
    auto ta = makeScalarTexture(2, 2, a, std::nullopt), tb = makeScalarTexture(2, 2, b, std::nullopt);
    auto binding = bind(ta);
    binding.textureB = tb.id();
    binding.alpha = 0.5f;
    // LUT(0.4) is pure green; a colour blend of LUT(0.2) and LUT(0.6) would be (0.25, 1, 0.25)/...
    EXPECT_DN_NEAR(render(*r, {binding}), dn(colourAt(0.4f)));
    binding.alpha = 0.0f;
    EXPECT_DN_NEAR(render(*r, {binding}), dn(colourAt(0.2f)));
    binding.alpha = 1.0f;
    EXPECT_DN_NEAR(render(*r, {binding}), dn(colourAt(0.6f)));
}

// interpolate "arrival" (issue 6): class data switch per pixel when alpha passes the pixel's
// threshold (from anim::computeArrivalThresholds), so the burn front sweeps from the old
// perimeter to the new one and no class is ever blended.
TEST_F(DataLayerGLTest, ArrivalSweepsTheFrontWithoutBlendingClasses) {
    CompositeProgramDesc desc{{{LayerKind::Sequence, LayerOp::Over, -1}}, {}, 1};
    desc.layers[0].arrival = true;
    auto r = TerrainRenderer::create(desc);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    makeLut();  // class 0 -> blue, class 1 -> (64, 0, 191), class 4 would be red
    r->setLut(0, mLutBinding);
    // 64 x 64 texels over the 1 km tile: burned (class 1) west of 250 m in frame 0, west of
    // 750 m in frame 1. Pixel centres fall between texel pairs of the same class.
    constexpr int n = 64;
    std::vector<float> f0(n * n), f1(n * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            f0[std::size_t(y * n + x)] = x < 16 ? 1.0f : 0.0f;
            f1[std::size_t(y * n + x)] = x < 48 ? 1.0f : 0.0f;
        }
    std::vector<float> thr;
    anim::computeArrivalThresholds(f0, f1, n, n, std::nullopt, thr);
    ASSERT_EQ(thr.size(), f0.size());
    auto t0 = makeScalarTexture(n, n, f0.data(), std::nullopt);
    auto t1 = makeScalarTexture(n, n, f1.data(), std::nullopt);
    auto tt = makeScalarTexture(n, n, thr.data(), std::nullopt);
    auto binding = bind(t0);
    binding.textureB = t1.id();
    binding.textureT = tt.id();
    binding.westT = 0;
    binding.northT = 1000;
    binding.widthT = 1000;
    binding.heightT = 1000;
    // Burned columns (pixel x < front) for each alpha: the front moves from 250 m to 750 m.
    for (float alpha : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        binding.alpha = alpha;
        render(*r, {binding});
        auto img = mTarget->readColor();
        int burned = 0;
        for (int x = 0; x < kSize; ++x) {
            const auto* p = img.pixel(x, kSize / 2);
            const glm::ivec3 c(p[0], p[1], p[2]);
            const bool isBurned = std::abs(c.r - lutDn(1).r) <= 1 && std::abs(c.b - lutDn(1).b) <= 1;
            const bool isUnburned = std::abs(c.r - lutDn(0).r) <= 1 && std::abs(c.b - lutDn(0).b) <= 1;
            ASSERT_TRUE(isBurned || isUnburned)
                << "alpha " << alpha << " pixel " << x << " blends classes: " << c.r << "," << c.b;
            burned += isBurned;
            if (x > 0 && isBurned) {
                const auto* q = img.pixel(x - 1, kSize / 2);
                EXPECT_EQ(q[0], p[0]) << "alpha " << alpha << ": burned pixel " << x
                                      << " east of an unburned one (the front is not one line)";
            }
        }
        // The front is at 250 m + alpha * 500 m; the view spans x 250..750 m (range 600 m at
        // 45 degrees), so alpha of the 32 columns are burned, within one pixel.
        EXPECT_NEAR(burned, alpha * kSize, 1.5) << "alpha " << alpha;
    }
}

TEST_F(LayerCompositingGLTest, HighlightLensRaisesInsideLowersOutside) {
    CompositeProgramDesc desc{{}, {{LensKind::Highlight, -1, -1}}, 0};
    auto r = TerrainRenderer::create(desc);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    LensBinding lens;
    lens.centre = {500.0, 500.0};
    lens.radii = {200.0, 200.0};
    lens.softEdge = 0.05f;
    lens.insideGain = 1.5f;
    lens.outsideGain = 0.5f;
    lens.enabled = true;
    r->setLens(0, lens);
    EXPECT_DN_NEAR(render(*r, {}), dn(kBase * 1.5f));
    // A corner pixel is far outside the 200 m lens.
    EXPECT_DN_NEAR(render(*r, {}, 1, 1), dn(kBase * 0.5f));
}

TEST_F(LayerCompositingGLTest, VisibilityLensSwapsLayersInside) {
    CompositeProgramDesc desc{{{LayerKind::Thematic, LayerOp::Over, -1},
                               {LayerKind::Thematic, LayerOp::Over, -1}},
                              {{LensKind::Visibility, 1, 0}},
                              0};
    auto r = TerrainRenderer::create(desc);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    LensBinding lens;
    lens.centre = {500.0, 500.0};
    lens.radii = {200.0, 200.0};
    lens.softEdge = 0.05f;
    lens.enabled = true;
    r->setLens(0, lens);
    auto red = solid({1, 0, 0, 1}), blue = solid({0, 0, 1, 1});
    EXPECT_DN_NEAR(render(*r, {bind(red), bind(blue)}), glm::ivec3(0, 0, 255));
    EXPECT_DN_NEAR(render(*r, {bind(red), bind(blue)}, 1, 1), glm::ivec3(255, 0, 0));
}

TEST_F(LayerCompositingGLTest, RotatedEllipticalLensAndSoftEdge) {
    CompositeProgramDesc desc{{}, {{LensKind::Highlight, -1, -1}}, 0};
    auto r = TerrainRenderer::create(desc);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    LensBinding lens;
    lens.centre = {500.0, 500.0};
    lens.radii = {200.0, 60.0};  // long and thin...
    lens.rotationDeg = 90.0;     // ...turned to run north-south
    lens.softEdge = 0.3f;
    lens.insideGain = 1.5f;
    lens.outsideGain = 0.5f;
    lens.enabled = true;
    r->setLens(0, lens);
    // The view is north-up, about 15.5 m per pixel around the centre pixel (16, 16).
    EXPECT_DN_NEAR(render(*r, {}, 16, 16), dn(kBase * 1.5f));
    EXPECT_DN_NEAR(render(*r, {}, 16, 10), dn(kBase * 1.5f));  // 93 m north: inside
    EXPECT_DN_NEAR(render(*r, {}, 4, 16), dn(kBase * 0.5f));   // 186 m west: outside
    EXPECT_DN_NEAR(render(*r, {}, 16, 0), dn(kBase * 0.5f));   // 248 m north: outside
    // 171 m north is in the soft rim (r = 0.86 of the 200 m axis): strictly between the gains.
    const glm::ivec3 rim = render(*r, {}, 16, 5);
    EXPECT_LT(rim.b, dn(kBase * 1.5f).b - 5);
    EXPECT_GT(rim.b, dn(kBase * 0.5f).b + 5);
}

TEST(LayerStackTest, ArrivalSequenceSwitchesOnAThresholdTexture) {
    CompositeProgramDesc desc{{{LayerKind::Sequence, LayerOp::Over, -1}}, {}, 1};
    EXPECT_EQ(textureUnitsNeeded(desc), 4);  // elevation LUT, transfer LUT, two frames
    auto data = generateCompositeShader(desc, 16);
    ASSERT_TRUE(data.ok());
    EXPECT_NE(data->find("mix(d0, e0, uLayerParam0.y)"), std::string::npos);
    EXPECT_EQ(data->find("uLayerT0"), std::string::npos);
    desc.layers[0].arrival = true;
    EXPECT_EQ(textureUnitsNeeded(desc), 5);  // + the pair's thresholds
    auto arrival = generateCompositeShader(desc, 16);
    ASSERT_TRUE(arrival.ok());
    EXPECT_NE(arrival->find("uniform sampler2D uLayerT0;"), std::string::npos);
    EXPECT_NE(arrival->find("uLayerParam0.y >= t0.r / max(t0.g, 1e-6) ? e0 : d0"), std::string::npos);
    EXPECT_EQ(arrival->find("mix(d0, e0"), std::string::npos) << "classes must never be mixed";
}

TEST(LayerStackTest, TooManyLayersIsReported) {
    CompositeProgramDesc desc;
    for (int i = 0; i < 20; ++i) desc.layers.push_back({LayerKind::Thematic, LayerOp::Over, -1});
    auto s = generateCompositeShader(desc, 16);
    ASSERT_FALSE(s.ok());
    EXPECT_TRUE(s.diagnostics.has("RENDER_TOO_MANY_LAYERS"));
    EXPECT_EQ(textureUnitsNeeded(desc), 21);
}

TEST(LayerStackTest, BlendWithoutVisibilitySourceIsReported) {
    CompositeProgramDesc desc{{{LayerKind::Thematic, LayerOp::Blend, 5}}, {}, 0};
    auto s = generateCompositeShader(desc, 16);
    ASSERT_FALSE(s.ok());
    EXPECT_TRUE(s.diagnostics.has("RENDER_BAD_BLEND"));
}

}  // namespace
}  // namespace kiosk::render
