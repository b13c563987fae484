// Projective mappings on a flat 1 km tile (issue 8): each blend mode and the colour matrix
// against hand-computed pixels, ordering, testAABB2D, and scalar data through a LUT.
#include "runtime/mapping/MappingModel.h"
#include "runtime/render/MappingSet.h"
#include "runtime/render/TerrainRenderer.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/MeshFixtures.h"
#include "tests/support/PixelAssert.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kiosk::render {
namespace {

constexpr int kSize = 32;
const glm::vec3 kBase(0.2f, 0.4f, 0.6f);
const glm::vec4 kSrc(0.8f, 0.2f, 0.4f, 0.5f);

using test::dn;

class MappingGLTest : public test::EglTest {
protected:
    void SetUp() override {
        test::EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        mTarget = std::make_unique<gl::RenderTarget>(makeTarget(kSize, kSize));
        mMesh = GpuMesh::upload(test::gridMesh(3, 500.0, [](double, double) { return 0.0; }));
        mCamera =
            math::Camera::fromViewpoint({{500.0, 500.0, 0.0}, 0.0, -89.9, 600.0}, kSize, kSize);
        mCamera.fitClipPlanes({0, 0, -1}, {1000, 1000, 1});
        auto set = MappingSet::create(mCaps, 64);
        ASSERT_TRUE(set.ok()) << set.diagnostics.format();
        mSet = std::make_unique<MappingSet>(std::move(*set.value));
        CompositeProgramDesc desc;
        desc.mappingCapacity = mSet->capacity();
        auto r = TerrainRenderer::create(desc, mCaps.maxTextureUnits);
        ASSERT_TRUE(r.ok()) << r.diagnostics.format();
        mRenderer = std::make_unique<TerrainRenderer>(std::move(*r.value));
        mRenderer->setMappings(mSet.get());
    }

    int solidLayer(glm::vec4 c) {
        std::vector<std::uint8_t> px(4 * 4 * 4);
        for (int i = 0; i < 16; ++i)
            for (int k = 0; k < 4; ++k)
                px[std::size_t(i * 4 + k)] = std::uint8_t(std::lround(c[k] * 255.0f));
        return mSet->addImage(4, 4, px.data());
    }

    /** A mapping over [x0, x1] x [y0, y1] (scene metres, plane z = 0). */
    static MappingGpu rect(int layer, double x0, double y0, double x1, double y1, int src,
                           int dst) {
        mapping::MappingState s;
        s.origin = {(x0 + x1) / 2, (y0 + y1) / 2, 0};
        s.u = {x1 - x0, 0, 0};
        s.v = {0, y1 - y0, 0};
        auto t = mapping::textureTransform(s, glm::dvec3(0.0));
        MappingGpu m;
        m.rowS = glm::vec4(t->rowS);
        m.rowT = glm::vec4(t->rowT);
        m.textureMatrix = glm::mat3(t->textureMatrix);
        m.layer = layer;
        m.srcFactor = src;
        m.dstFactor = dst;
        return m;
    }

    static MappingGpu whole(int layer, int src, int dst) {
        return rect(layer, 0, 0, 1000, 1000, src, dst);
    }

    gl::Image render(const std::vector<MappingGpu>& maps, bool context = false,
                     const glm::mat4& contextMatrix = glm::mat4(1.0f)) {
        mSet->setMappings(maps, context, contextMatrix);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        TerrainStyle style;
        style.geometryLighting = 0.0f;
        style.elevationLutWeight = 0.0f;
        style.baseColor = glm::vec4(kBase, 1.0f);
        mRenderer->begin(mCamera, glm::dvec3(0.0), style);
        mRenderer->draw(mMesh, glm::dvec3(0.0));
        mRenderer->end();
        EXPECT_GL_OK();
        return mTarget->readColor();
    }

    static glm::ivec3 at(const gl::Image& img, int x, int y) {
        const auto* p = img.pixel(x, y);
        return {p[0], p[1], p[2]};
    }

    glm::ivec3 centre(const std::vector<MappingGpu>& maps) {
        return at(render(maps), kSize / 2, kSize / 2);
    }

    /** Scene position on z = 0 of pixel (x, row from the top). */
    glm::dvec2 worldAt(int x, int rowTop) const {
        const glm::dmat4 view = mCamera.view(), proj = mCamera.projection();
        const glm::dvec4 vp(0, 0, kSize, kSize);
        const glm::dvec3 w(x + 0.5, kSize - 1 - rowTop + 0.5, 0.0);
        const glm::dvec3 a = glm::unProject(w, view, proj, vp);
        const glm::dvec3 b = glm::unProject(glm::dvec3(w.x, w.y, 1.0), view, proj, vp);
        const double t = -a.z / (b.z - a.z);
        return glm::dvec2(a + (b - a) * t);
    }

    std::unique_ptr<gl::RenderTarget> mTarget;
    GpuMesh mMesh;
    math::Camera mCamera;
    std::unique_ptr<MappingSet> mSet;
    std::unique_ptr<TerrainRenderer> mRenderer;
};

// config::BlendFactor order.
enum : int {
    kZero,
    kOne,
    kSrcColor,
    kOneMinusSrcColor,
    kDstColor,
    kOneMinusDstColor,
    kSrcAlpha,
    kOneMinusSrcAlpha
};

TEST_F(MappingGLTest, NoMappingsLeavesTheStack) {
    mSet->commit();
    EXPECT_DN_NEAR(centre({}), dn(kBase));
}

TEST_F(MappingGLTest, BlendModes) {
    const int layer = solidLayer(kSrc);
    mSet->commit();
    const glm::vec3 s(kSrc), d(kBase);
    const float a = kSrc.a;
    {
        SCOPED_TRACE("replace");
        EXPECT_DN_NEAR(centre({whole(layer, kOne, kZero)}), dn(s));
    }
    {
        SCOPED_TRACE("multiply");
        EXPECT_DN_NEAR(centre({whole(layer, kDstColor, kZero)}), dn(s * d));
    }
    {
        SCOPED_TRACE("alpha blend");
        EXPECT_DN_NEAR(centre({whole(layer, kSrcAlpha, kOneMinusSrcAlpha)}),
                       dn(s * a + d * (1 - a)));
    }
    {
        SCOPED_TRACE("add (clamped)");
        EXPECT_DN_NEAR(centre({whole(layer, kOne, kOne)}), dn(s + d));
    }
    {
        SCOPED_TRACE("add weighted");
        EXPECT_DN_NEAR(centre({whole(layer, kSrcAlpha, kOne)}), dn(s * a + d));
    }
    EXPECT_DN_NEAR(centre({whole(layer, kOneMinusDstColor, kOneMinusSrcColor)}),
                   dn(s * (glm::vec3(1) - d) + d * (glm::vec3(1) - s)));
    // Opacity scales the source alpha.
    auto half = whole(layer, kSrcAlpha, kOneMinusSrcAlpha);
    half.opacity = 0.5f;
    {
        SCOPED_TRACE("opacity");
        EXPECT_DN_NEAR(centre({half}), dn(s * (a * 0.5f) + d * (1 - a * 0.5f)));
    }
}

TEST_F(MappingGLTest, ColourMatrixAppliesToRgbOnly) {
    const int layer = solidLayer(kSrc);
    mSet->commit();
    auto m = whole(layer, kSrcAlpha, kOneMinusSrcAlpha);
    // Rows: r' = g, g' = 0.5 b + 0.1, b' = r; alpha untouched (the paper's M_C).
    const glm::mat4 cm = glm::transpose(glm::mat4(0, 1, 0, 0,      //
                                                  0, 0, 0.5, 0.1,  //
                                                  1, 0, 0, 0,      //
                                                  0, 0, 0, 1));
    m.colorMatrix = cm;
    const glm::vec3 src(kSrc.g, 0.5f * kSrc.b + 0.1f, kSrc.r);
    EXPECT_DN_NEAR(centre({m}), dn(src * kSrc.a + kBase * (1 - kSrc.a)));
}

TEST_F(MappingGLTest, LaterMappingsDrawOverEarlierAndOutsideIsUntouched) {
    const int red = solidLayer({1, 0, 0, 1});
    const int green = solidLayer({0, 1, 0, 1});
    mSet->commit();
    EXPECT_DN_NEAR(centre({whole(red, kOne, kZero), whole(green, kOne, kZero)}), dn({0, 1, 0}));
    EXPECT_DN_NEAR(centre({whole(green, kOne, kZero), whole(red, kOne, kZero)}), dn({1, 0, 0}));
    // Green only over the west half of the view: east pixels fail testAABB2D and keep the base.
    auto img = render(
        {whole(red, kSrcAlpha, kOneMinusSrcAlpha), rect(green, 0, 0, 500, 1000, kOne, kZero)});
    EXPECT_DN_NEAR(at(img, 4, kSize / 2), dn({0, 1, 0}));
    EXPECT_DN_NEAR(at(img, kSize - 4, kSize / 2), dn({1, 0, 0}));
    auto only = render({rect(green, 0, 0, 500, 1000, kOne, kZero)});
    EXPECT_DN_NEAR(at(only, kSize - 4, kSize / 2), dn(kBase));
}

TEST_F(MappingGLTest, TextureMatrixPicksAnAtlasCellInsideTheRectangleOnly) {
    // 4x4 atlas of 2x2 cells, top row first: red, green / blue, white.
    const glm::u8vec4 cells[2][2] = {{{255, 0, 0, 255}, {0, 255, 0, 255}},
                                     {{0, 0, 255, 255}, {255, 255, 255, 255}}};
    std::vector<std::uint8_t> px(4 * 4 * 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 4; ++c)
                px[std::size_t((y * 4 + x) * 4 + c)] = cells[y / 2][x / 2][c];
    const int atlas = mSet->addImage(4, 4, px.data());
    mSet->commit();
    auto m = rect(atlas, 300, 300, 700, 700, kOne, kZero);
    // Cell (1, 0) - column 1, top row: s' = s/2 + 1/2, t' = t/2 + 1/2 (t runs up the image).
    m.textureMatrix = glm::transpose(glm::mat3(0.5f, 0, 0.5f, 0, 0.5f, 0.5f, 0, 0, 1));
    auto img = render({m});
    EXPECT_DN_NEAR(at(img, kSize / 2, kSize / 2), dn({0, 1, 0}));
    // East of x = 700 m M_T would still land inside the atlas; the footprint is the rectangle.
    const int east = kSize - 1;
    ASSERT_GT(worldAt(east, kSize / 2).x, 710.0);
    EXPECT_DN_NEAR(at(img, east, kSize / 2), dn(kBase));
}

TEST_F(MappingGLTest, ContextMatrixDimsOutsideTheFocus) {
    const int white = solidLayer({1, 1, 1, 1});
    mSet->commit();
    auto focus = rect(white, 0, 0, 500, 1000, kDstColor, kZero);  // multiply by 1: unchanged
    focus.focus = true;
    const glm::mat4 dim = glm::mat4(0.5f);  // scale rgb by 0.5 (w row irrelevant)
    auto img = render({focus}, true, dim);
    EXPECT_DN_NEAR(at(img, 4, kSize / 2), dn(kBase));
    EXPECT_DN_NEAR(at(img, kSize - 4, kSize / 2), dn(kBase * 0.5f));
}

TEST_F(MappingGLTest, ScalarDataThroughTheLutWithinOneDn) {
    // Values 0..100 along x on a 64x64 raster exactly covering the tile; LUT ramps red up and
    // green down over [0, 100]. Expected colour comes from each pixel's own scene position.
    constexpr int n = 64;
    std::vector<float> values(n * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            values[std::size_t(y * n + x)] = 100.0f * (float(x) + 0.5f) / float(n);
    values[0] = NAN;  // nodata far outside the view: must not disturb the rest
    std::vector<std::uint8_t> lut(MappingSet::kLutEntries * 4);
    for (int i = 0; i < MappingSet::kLutEntries; ++i) {
        const double t = double(i) / (MappingSet::kLutEntries - 1);
        lut[std::size_t(i) * 4 + 0] = std::uint8_t(std::lround(255 * t));
        lut[std::size_t(i) * 4 + 1] = std::uint8_t(std::lround(255 * (1 - t)));
        lut[std::size_t(i) * 4 + 2] = 77;
        lut[std::size_t(i) * 4 + 3] = 255;
    }
    const int layer = mSet->addScalar(n, n, values.data(), 0.0, 100.0);
    const int row = mSet->addLut(lut, {0, 0, 0, 0}, {0, 0, 0, 0});
    ASSERT_GE(layer, 0);
    ASSERT_GE(row, 0);
    mSet->commit();
    auto m = whole(layer, kOne, kZero);
    m.lut = row;
    auto img = render({m});
    for (int x = 2; x < kSize; x += 5) {
        const glm::dvec2 w = worldAt(x, kSize / 2);
        const double t = w.x / 1000.0;  // value / 100
        SCOPED_TRACE("pixel " + std::to_string(x) + " at x = " + std::to_string(w.x));
        EXPECT_DN_NEAR(at(img, x, kSize / 2), dn(glm::vec3(float(t), float(1 - t), 77 / 255.0f)));
    }
}

TEST_F(MappingGLTest, BlockUploadsOnlyOnChange) {
    const int layer = solidLayer(kSrc);
    mSet->commit();
    const auto before = mSet->blockUploads();
    render({whole(layer, kOne, kZero)});
    render({whole(layer, kOne, kZero)});
    EXPECT_EQ(mSet->blockUploads(), before + 1);
    render({whole(layer, kOne, kOne)});
    EXPECT_EQ(mSet->blockUploads(), before + 2);
}

TEST_F(MappingGLTest, BeyondTheBlockCapacityTheRestIsNotDrawn) {
    // A GPU whose uniform blocks hold two mappings: the third (green, replace) is dropped.
    gl::Caps small = mCaps;
    small.maxUniformBlockSize = 16 * (MappingSet::kHeaderVec4 + 2 * MappingSet::kVec4PerMapping);
    auto set = MappingSet::create(small, 16);
    ASSERT_TRUE(set.ok()) << set.diagnostics.format();
    ASSERT_EQ(set->capacity(), 2);
    std::vector<std::uint8_t> px;
    for (glm::u8vec4 c :
         {glm::u8vec4(255, 0, 0, 255), glm::u8vec4(0, 0, 255, 255), glm::u8vec4(0, 255, 0, 255)}) {
        px.assign(16 * 4, 0);
        for (int i = 0; i < 16; ++i)
            for (int k = 0; k < 4; ++k) px[std::size_t(i * 4 + k)] = c[k];
        set->addImage(4, 4, px.data());
    }
    set->commit();
    CompositeProgramDesc desc;
    desc.mappingCapacity = set->capacity();
    auto r = TerrainRenderer::create(desc, mCaps.maxTextureUnits);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    mRenderer = std::make_unique<TerrainRenderer>(std::move(*r.value));
    mSet = std::make_unique<MappingSet>(std::move(*set.value));
    mRenderer->setMappings(mSet.get());
    EXPECT_DN_NEAR(centre({whole(0, kOne, kZero), whole(1, kOne, kZero), whole(2, kOne, kZero)}),
                   dn({0, 0, 1}));
}

TEST(MappingSetLimits, CapacityFollowsTheBlockSize) {
    EXPECT_EQ(MappingSet::capacityFor(16384), MappingSet::kMaxMappings);
    EXPECT_EQ(MappingSet::capacityFor(16 * (5 + 12 * 3)), 3);
    EXPECT_EQ(MappingSet::capacityFor(64), 0);
}

}  // namespace
}  // namespace kiosk::render
