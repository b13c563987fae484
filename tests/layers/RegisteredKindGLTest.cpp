// A layer kind defined and registered here (not in layers/, scene/ or render/) plans its
// sources from store metadata and renders through the one-pass compositor: the seam between
// the compositor and a kind is the LayerShader interface and one registration line. A kind also
// brings its scenario section: a scenario names it, its own reader reads its options.
#include "config/KindSection.h"
#include "config/ScenarioReader.h"
#include "layers/ImageryKind.h"
#include "layers/Registry.h"
#include "layers/SourcedSection.h"
#include "runtime/render/TerrainRenderer.h"
#include "runtime/render/Textures.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/MeshFixtures.h"
#include "tests/support/PixelAssert.h"
#include "tests/unit/config/ConfigTestSupport.h"

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

/** The scenario kind's own option: which channels it swaps (`"swap": "rb"` or `"rg"`). */
struct SwapOptions : config::KindOptions {
    std::string channels = "rb";
};

/** Its own reader: an imagery layer's source rules, and "swap". */
class SwapSection : public config::KindSection {
public:
    std::vector<std::string> properties() const override { return {"swap"}; }
    void read(config::reader::Ctx& c, const config::reader::Obj& o,
              config::Layer& l) const override {
        using namespace config::reader;
        refuseOperands(c, o);
        productOptions(c, o, l);
        checkSourced(c, o, l, SourcedValues::Imagery, false);
        static const EnumTable<std::string> kSwaps = {{"rb", "rb"}, {"rg", "rg"}};
        auto options = std::make_shared<SwapOptions>();
        assign(options->channels, o.oneOf("swap", kSwaps));
        l.options = options;
    }
    std::string schema() const override {
        return R"({"properties": {"swap": {"enum": ["rb", "rg"],
                   "description": "Channels the test kind swaps."}}, "required": ["source"]})";
    }
};

/** Swaps the channels its layer's options name (red and green: no helper function). */
class ScenarioSwapKind : public layers::ImageryKind {
public:
    std::string plan(const config::Layer& layer, const layers::StoreView& store,
                     layers::SourcePlan& out) const override {
        std::string problem = ImageryKind::plan(layer, store, out);
        const auto* options = dynamic_cast<const SwapOptions*>(layer.options.get());
        if (options && options->channels == "rg")
            out.piece = std::make_shared<layers::ExpressionShader>("$T.grba", false);
        else
            out.piece = std::make_shared<SwapShader>();
        return problem;
    }
    std::shared_ptr<const layers::LayerShader> shader(
        const layers::SourcePlan& plan) const override {
        return plan.piece;
    }
    std::shared_ptr<const config::KindSection> section() const override {
        return std::make_shared<SwapSection>();
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

    /** A store holding one imagery layer "photo" of 3 levels. */
    static io::StoreInfo photoStore() {
        io::StoreInfo store;
        io::LayerInfo imagery;
        imagery.name = "photo";
        imagery.kind = io::LayerKind::Imagery;
        imagery.levels = 3;
        store.layers.push_back(imagery);
        return store;
    }
    /**
     * The centre pixel of `desc` drawn over the flat grid, layer i showing a solid texture of
     * colour `layers[i].first` at opacity `layers[i].second`; (-1, -1, -1) if it did not build.
     */
    glm::ivec3 centre(const render::CompositeProgramDesc& desc,
                      const std::vector<std::pair<glm::vec4, float>>& layers) {
        auto r = render::TerrainRenderer::create(desc, 16);
        EXPECT_TRUE(r.ok()) << r.diagnostics.format();
        if (!r.ok()) return glm::ivec3(-1);
        std::vector<gl::Texture> textures;
        for (const auto& l : layers) textures.push_back(solid(l.first));
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        render::TerrainStyle style;
        style.geometryLighting = 0.0f;
        style.elevationLutWeight = 0.0f;
        style.baseColor = glm::vec4(0.2f, 0.4f, 0.6f, 1.0f);
        r->begin(mCamera, glm::dvec3(0.0), style);
        for (std::size_t i = 0; i < layers.size(); ++i)
            r->setLayer(int(i), bind(textures[i], layers[i].second));
        r->draw(mMesh, glm::dvec3(0.0));
        r->end();
        EXPECT_GL_OK();
        auto img = mTarget->readColor();
        const auto* p = img.pixel(kSize / 2, kSize / 2);
        return glm::ivec3(p[0], p[1], p[2]);
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
    const io::StoreInfo store = photoStore();
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
    EXPECT_DN_NEAR(centre(desc, {{{1, 0, 0, 1}, 1.0f}, {{0, 1, 0, 1}, 0.5f}}),
                   dn(glm::vec3(0.0f, 0.5f, 0.5f)));
}

TEST_F(RegisteredKindGLTest, KindNamedInAScenarioIsReadByItsOwnReader) {
    layers::registry().add("test-scenario-swap", std::make_unique<ScenarioSwapKind>());
    auto scenario = [](const std::string& layers) {
        return R"({"version": 1, "stores": {"s": "s.gpkg"}, "terrain": {"store": "s"},
                   "layers": [)" +
               layers + "]}";
    };
    const std::string photo = R"("source": {"store": "s", "layer": "photo"})";
    auto r = config::parseScenario(
        scenario(R"({"id": "p", "kind": "test-scenario-swap", )" + photo + R"(, "swap": "rg"})"),
        "swap.json");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const config::Layer& layer = r.value->layers.at(0);
    EXPECT_EQ(layer.kindName, "test-scenario-swap");
    EXPECT_EQ(layer.kind, config::LayerKind::Registered);
    const auto* options = dynamic_cast<const SwapOptions*>(layer.options.get());
    ASSERT_NE(options, nullptr) << "the kind's own reader did not run";
    EXPECT_EQ(options->channels, "rg");

    // Its mistakes are its reader's, with the pointer; its property is its kind's only; a
    // built-in rule it adopted (a source) keeps the built-in message.
    auto bad = config::parseScenario(
        scenario(R"({"id": "p", "kind": "test-scenario-swap", )" + photo + R"(, "swap": "xy"})"),
        "bad.json");
    EXPECT_TRUE(test::isOneErrorLine(bad.diagnostics, "SCENARIO_BAD_VALUE", "/layers/0/swap",
                                     "unknown swap \"xy\"; expected one of rb, rg"));
    auto elsewhere = config::parseScenario(
        scenario(R"({"id": "p", "kind": "thematic", )" + photo + R"(, "swap": "rg"})"),
        "elsewhere.json");
    EXPECT_TRUE(test::isOneErrorLine(elsewhere.diagnostics, "SCENARIO_UNKNOWN_PROPERTY",
                                     "/layers/0/swap", "unknown property \"swap\""));
    auto sourceless = config::parseScenario(
        scenario(R"({"id": "p", "kind": "test-scenario-swap"})"), "sourceless.json");
    EXPECT_TRUE(test::isOneErrorLine(sourceless.diagnostics, "SCENARIO_MISSING", "/layers/0",
                                     "missing required property \"source\""));

    // Its schema fragment joins the scenario schema: the kind, its property, its condition.
    const auto schema = nlohmann::json::parse(
        config::scenarioSchema(test::slurp("config/schema/scenario.schema.json")));
    const auto& def = schema["$defs"]["Layer"];
    const auto& kinds = def["properties"]["kind"]["enum"];
    EXPECT_NE(std::find(kinds.begin(), kinds.end(), "test-scenario-swap"), kinds.end());
    EXPECT_EQ(def["properties"]["swap"]["enum"], nlohmann::json({"rb", "rg"}));
    EXPECT_EQ(def["allOf"].back()["if"]["properties"]["kind"]["const"], "test-scenario-swap");
    EXPECT_EQ(def["allOf"].back()["then"]["required"], nlohmann::json({"source"}));

    // The layer as read, planned and drawn: red through "rg" is green.
    const io::StoreInfo store = photoStore();
    const std::string elevation = "elevation";
    const layers::Kind* kind = layers::registry().find(layer.kindName);
    ASSERT_NE(kind, nullptr);
    layers::SourcePlan plan;
    ASSERT_EQ(kind->plan(layer, {store, elevation}, plan), "");
    render::CompositeProgramDesc desc;
    render::CompositeLayer l;
    l.op = render::LayerOp::Over;
    l.shader = kind->shader(plan);
    desc.layers.push_back(l);
    EXPECT_DN_NEAR(centre(desc, {{{1, 0, 0, 1}, 1.0f}}), dn(glm::vec3(0.0f, 1.0f, 0.0f)));
}

}  // namespace
}  // namespace kiosk
