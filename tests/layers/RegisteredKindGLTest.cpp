// A layer kind defined and registered here (not in layers/, scene/ or render/) plans its
// sources from store metadata and renders through the one-pass compositor: the seam between
// the compositor and a kind is the LayerShader interface and one registration line.
#include "layers/ImageryKind.h"
#include "layers/Registry.h"
#include "runtime/render/TerrainRenderer.h"
#include "runtime/render/Textures.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/MeshFixtures.h"
#include "tests/support/PixelAssert.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kiosk {
namespace {

using test::dn;

constexpr int kSize = 32;

/** Swaps red and blue of its imagery through a helper function every such layer shares. */
class SwapShader : public layers::LayerShader {
public:
    const char* helpers() const override {
        // Emitted once per program: a second copy would not compile (redefinition).
        return "vec4 swapRedBlue(vec4 c) { return c.bgra; }\n";
    }
    void sample(std::ostream& s, int i, int) const override {
        s << "    vec4 L" << i << " = swapRedBlue(texture(uLayer" << i << ", uv" << i << "));\n";
    }
};

class SwapKind : public layers::ImageryKind {
public:
    std::shared_ptr<const layers::LayerShader> shader(const layers::SourcePlan&) const override {
        return std::make_shared<SwapShader>();
    }
};

class RegisteredKindGLTest : public test::EglTest {
protected:
    void SetUp() override {
        test::EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        mTarget = std::make_unique<gl::RenderTarget>(makeTarget(kSize, kSize));
        mMesh =
            render::GpuMesh::upload(test::gridMesh(3, 500.0, [](double, double) { return 0.0; }));
        mCamera =
            math::Camera::fromViewpoint({{500.0, 500.0, 0.0}, 0.0, -89.9, 600.0}, kSize, kSize);
        mCamera.fitClipPlanes({0, 0, -1}, {1000, 1000, 1});
    }

    static gl::Texture solid(glm::vec4 c) {
        std::uint8_t px[16];
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 4; ++k) px[i * 4 + k] = std::uint8_t(std::lround(c[k] * 255.0f));
        return render::makeRgbaTexture(2, 2, px, false);
    }
    static render::LayerBinding bind(const gl::Texture& t, float strength) {
        render::LayerBinding b;
        b.texture = t.id();
        b.west = 0;
        b.north = 1000;
        b.width = 1000;
        b.height = 1000;
        b.strength = strength;
        b.valid = true;
        return b;
    }

    std::unique_ptr<gl::RenderTarget> mTarget;
    render::GpuMesh mMesh;
    math::Camera mCamera;
};

TEST_F(RegisteredKindGLTest, TestKindPlansItsSourceAndRenders) {
    layers::registry().add("test-swap", std::make_unique<SwapKind>());
    const layers::Kind* kind = layers::registry().find("test-swap");
    ASSERT_NE(kind, nullptr);
    EXPECT_EQ(layers::registry().find("test-nothing"), nullptr);

    // Its sources, planned from store metadata like any kind's.
    io::StoreInfo store;
    io::LayerInfo imagery;
    imagery.name = "photo";
    imagery.kind = io::LayerKind::Imagery;
    imagery.levels = 3;
    store.layers.push_back(imagery);
    const std::string elevation = "elevation";
    config::Layer layer;
    layer.source.layer = "photo";
    layers::SourcePlan plan;
    EXPECT_EQ(kind->plan(layer, {store, elevation}, plan), "");
    EXPECT_EQ(plan.source, layers::SourceKind::Imagery);
    EXPECT_EQ(plan.table, "photo");
    EXPECT_EQ(plan.maxLevel, 2);
    layer.source.layer = "missing";
    layers::SourcePlan none;
    EXPECT_NE(kind->plan(layer, {store, elevation}, none), "");

    // Two layers of the kind in one program: red swapped to blue, then green (unchanged by the
    // swap) over it at half opacity.
    render::CompositeProgramDesc desc;
    for (int i = 0; i < 2; ++i) {
        render::CompositeLayer l;
        l.op = render::LayerOp::Over;
        l.shader = kind->shader(plan);
        desc.layers.push_back(l);
    }
    auto r = render::TerrainRenderer::create(desc, 16);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    auto red = solid({1, 0, 0, 1}), green = solid({0, 1, 0, 1});
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    render::TerrainStyle style;
    style.geometryLighting = 0.0f;
    style.elevationLutWeight = 0.0f;
    style.baseColor = glm::vec4(0.2f, 0.4f, 0.6f, 1.0f);
    r->begin(mCamera, glm::dvec3(0.0), style);
    r->setLayer(0, bind(red, 1.0f));
    r->setLayer(1, bind(green, 0.5f));
    r->draw(mMesh, glm::dvec3(0.0));
    r->end();
    EXPECT_GL_OK();
    auto img = mTarget->readColor();
    const auto* p = img.pixel(kSize / 2, kSize / 2);
    EXPECT_DN_NEAR(glm::ivec3(p[0], p[1], p[2]), dn(glm::vec3(0.0f, 0.5f, 0.5f)));
}

}  // namespace
}  // namespace kiosk
