// Derived products (issue 19) on real data: the ANUGA cairns run imported as a depth sequence.
// For sampled posts of a tile, the product layer's shader is drawn with that post's texel of the
// loader's product tile (layers/products/Derivations through loader::DerivedTiles, as the scene
// serves them: the state after the pair's first frame and the two frames) and the pixel is
// compared with the LUT colour of an independent
// computation over the raw frames (brute-force sampling of the linear series, not the
// product's closed forms): maximum and duration within 1 DN, arrival within one frame step.
// Also: the running state resumed across seeks equals a cold computation, and the ARR hazard
// classes on a synthetic depth/velocity field that crosses every threshold.
#include "layers/Registry.h"
#include "layers/products/Derivations.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "runtime/io/StoreReader.h"
#include "runtime/loader/DerivedTiles.h"
#include "runtime/render/TerrainRenderer.h"
#include "runtime/render/Textures.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/MeshFixtures.h"
#include "tests/support/PixelAssert.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>

namespace kiosk::layers {
namespace {

namespace fs = std::filesystem;
using test::dn;

constexpr int kSize = 16;
constexpr double kStart = 1773446400.0;  // 2026-03-14T00:00:00Z, the clock start (origin)
constexpr int kFrame = 30;               // the pair (30, 31) at alpha 0.4
constexpr double kAlpha = 0.4;
constexpr float kLutMax = 8.5f;  // LUT domain [0, 8.5] (m or min)

bool near1(glm::ivec3 a, glm::ivec3 e) {
    return std::abs(a.x - e.x) <= 1 && std::abs(a.y - e.y) <= 1 && std::abs(a.z - e.z) <= 1;
}
std::string text(glm::ivec3 c) {
    return "(" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " + std::to_string(c.z) +
           ")";
}

class ProductsGLTest : public test::EglTest {
protected:
    static void SetUpTestSuite() {
        sSww = test::sharedData("anuga_sww_flood_timeseries/cairns.sww");
        if (sSww.empty()) return;
        sDir = fs::temp_directory_path() / ("kiosk-products-" + std::to_string(::getpid()));
        fs::create_directories(sDir);
        import::ImportOptions o;
        o.quiet = true;
        o.store = sDir / "cairns.gpkg";
        o.name = "flood";
        o.start = kStart;
        o.wetThreshold = 0.01;
        sImport = import::importSequence({sSww}, o).format();
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        if (!sDir.empty()) fs::remove_all(sDir, ec);
    }
    void SetUp() override {
        test::EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        if (sSww.empty()) GTEST_SKIP() << "../shared/data/anuga_sww_flood_timeseries absent";
        ASSERT_EQ(sImport, "");
        auto reader = io::StoreReader::open(sDir / "cairns.gpkg");
        ASSERT_TRUE(reader.ok()) << reader.diagnostics.format();
        mReader = std::move(*reader.value);
        mSeq = mReader->info().findSequence("flood");
        ASSERT_NE(mSeq, nullptr);
        ASSERT_GT(mSeq->frameTimes.size(), std::size_t(kFrame + 1));
        // The finest tile holding the most wet posts at the test frame.
        const int level = mSeq->levels - 1;
        const auto& m = mReader->info().grid.levels[std::size_t(level)];
        std::size_t best = 0;
        for (int row = 0; row < m.matrixHeight; ++row)
            for (int col = 0; col < m.matrixWidth; ++col) {
                auto r = mReader->readSequenceFrame("flood", kFrame, {level, col, row});
                if (!r.ok()) continue;
                std::size_t wet = 0;
                for (float v : r->values) wet += v > 0.1f;
                if (wet > best) {
                    best = wet;
                    mTile = {level, col, row};
                }
            }
        ASSERT_GT(best, 1000u) << "no wet tile in the cairns run";
        for (int f = 0; f <= kFrame + 1; ++f) {
            auto r = mReader->readSequenceFrame("flood", f, mTile);
            ASSERT_TRUE(r.ok()) << r.diagnostics.format();
            mFrames.push_back(std::move(r->values));
            mPostsX = r->postsX;
        }
        mTarget = std::make_unique<gl::RenderTarget>(makeTarget(kSize, kSize));
        mMesh =
            render::GpuMesh::upload(test::gridMesh(3, 500.0, [](double, double) { return 0.0; }));
        mCamera =
            math::Camera::fromViewpoint({{500.0, 500.0, 0.0}, 0.0, -89.9, 600.0}, kSize, kSize);
        mCamera.fitClipPlanes({0, 0, -1}, {1000, 1000, 1});
        // Linear ramp LUT over [0, kLutMax]: red = v / kLutMax, blue = 1 - red.
        std::vector<std::uint8_t> lut(1024 * 4);
        for (int i = 0; i < 1024; ++i) {
            const float t = float(i) / 1023.0f;
            lut[std::size_t(i) * 4] = std::uint8_t(std::lround(t * 255.0f));
            lut[std::size_t(i) * 4 + 2] = std::uint8_t(std::lround((1.0f - t) * 255.0f));
            lut[std::size_t(i) * 4 + 3] = 255;
        }
        // Nodata transparent: the green base shows.
        mLut = render::makeEdgedLutTexture(1024, lut.data(), glm::vec4(-1.0f), glm::vec4(-1.0f),
                                           glm::vec4(0.0f));
    }

    static glm::ivec3 lutDn(double v) {
        const float t = std::clamp(float(v) / kLutMax, 0.0f, 1.0f);
        return dn(glm::vec3(t, 0.0f, 1.0f - t));
    }
    double minutes(int frame) const {
        return (mSeq->frameTimes[std::size_t(frame)] - kStart) / 60.0;
    }
    /** The raw series of post `i` at times t_0..t_k and the value at alpha in (k, k + 1). */
    double valueAt(std::size_t i, int frame, double alpha) const {
        return (1.0 - alpha) * mFrames[std::size_t(frame)][i] +
               alpha * mFrames[std::size_t(frame) + 1][i];
    }
    /**
     * Independent of the product code: walk the piecewise linear series up to (kFrame, kAlpha)
     * in 200 sub-steps per interval, calling `visit(time in minutes, value, sub-step length)`.
     */
    void walk(std::size_t i, const std::function<void(double, double, double)>& visit) const {
        constexpr int kSub = 200;
        visit(minutes(0), mFrames[0][i], 0.0);
        for (int f = 0; f <= kFrame; ++f) {
            const double span = minutes(f + 1) - minutes(f);
            const double upTo = f == kFrame ? kAlpha : 1.0;
            for (int s = 1; s <= int(upTo * kSub + 0.5); ++s) {
                const double a = double(s) / kSub;
                visit(minutes(f) + a * span, valueAt(i, f, a), span / kSub);
            }
        }
    }

    /** Plan a product layer of `kind` with the loader's product tile of frame kFrame. */
    struct Planned {
        SourcePlan plan;
        io::RasterTile state;
    };
    Planned planProduct(config::LayerKind kind, double threshold) {
        config::Layer layer;
        layer.id = "p";
        layer.kind = kind;
        layer.source.sequence = "flood";
        layer.transfer = "ramp";
        layer.product.threshold = threshold;
        layer.product.hasThreshold = true;
        layer.product.timeUnits = "min";
        layer.nodataAs = 0.0;  // as the scenarios: a dry cell counts as depth 0
        const std::string elevation = "elevation";
        StoreView view{mReader->info(), elevation};
        view.timeOrigin = kStart;
        Planned p;
        const Kind* k = registry().find(config::layerKindName(kind));
        EXPECT_NE(k, nullptr);
        if (!k) return p;
        EXPECT_EQ(k->plan(layer, view, p.plan), "");
        EXPECT_TRUE(p.plan.frames);
        if (!p.plan.frames) return p;
        loader::DerivedTiles tiles;
        Diagnostics d = tiles.compute(1, *p.plan.frames, *mReader, "flood", kFrame, mTile, p.state);
        EXPECT_EQ(p.state.channels, 4);
        EXPECT_FALSE(d.hasErrors()) << d.format();
        return p;
    }

    /** Draw the product with post `i`'s texel everywhere; the centre pixel. */
    glm::ivec3 drawPost(render::TerrainRenderer& r, const Planned& p, std::size_t i) {
        float texel[16];
        for (int k = 0; k < 16; ++k) texel[k] = p.state.values[i * 4 + std::size_t(k % 4)];
        auto t = render::makeProductTexture(2, 2, texel);
        render::LayerBinding lb;
        lb.texture = t.id();
        lb.west = 0;
        lb.north = 1000;
        lb.width = lb.height = 1000;
        lb.alpha = float(kAlpha);
        lb.valid = true;
        lb.product = glm::vec4(float(minutes(kFrame)), float(minutes(kFrame + 1) - minutes(kFrame)),
                               0.0f, 0.0f);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        render::TerrainStyle style;
        style.geometryLighting = 0.0f;
        style.elevationLutWeight = 0.0f;
        style.baseColor = glm::vec4(0, 1, 0, 1);  // green: the layer drew nothing
        r.begin(mCamera, glm::dvec3(0.0), style);
        r.setLayer(0, lb);
        r.draw(mMesh, glm::dvec3(0.0));
        r.end();
        auto img = mTarget->readColor();
        const auto* px = img.pixel(kSize / 2, kSize / 2);
        return {px[0], px[1], px[2]};
    }

    std::unique_ptr<render::TerrainRenderer> renderer(const Planned& p) {
        render::CompositeProgramDesc desc{
            {{render::LayerKind::Sequence, render::LayerOp::Over, -1}}, {}, 1};
        desc.layers[0].shader = registry()
                                    .find("maximum")  // any product kind: shader(plan) = piece
                                    ->shader(p.plan);
        auto r = render::TerrainRenderer::create(desc);
        EXPECT_TRUE(r.ok()) << r.diagnostics.format();
        if (!r) return nullptr;
        render::LutBinding lb;
        lb.texture = mLut.id();
        lb.size = 1024;
        lb.domainMin = 0.0f;
        lb.domainMax = kLutMax;
        r->setLut(0, lb);
        return std::make_unique<render::TerrainRenderer>(std::move(*r.value));
    }

    /** Posts valid in every frame (inside the model mesh), every 23rd. */
    std::vector<std::size_t> samplePosts() const {
        std::vector<std::size_t> out;
        for (std::size_t i = 0; i < mFrames[0].size(); i += 23) {
            bool ok = true;
            for (const auto& f : mFrames) ok = ok && !std::isnan(f[i]);
            if (ok) out.push_back(i);
        }
        return out;
    }

    static inline std::string sSww, sImport;
    static inline fs::path sDir;
    std::unique_ptr<io::StoreReader> mReader;
    const io::SequenceInfo* mSeq = nullptr;
    TileId mTile;
    int mPostsX = 0;
    std::vector<std::vector<float>> mFrames;
    std::unique_ptr<gl::RenderTarget> mTarget;
    render::GpuMesh mMesh;
    math::Camera mCamera;
    gl::Texture mLut;
};

TEST_F(ProductsGLTest, MaximumSoFarWithinOneDn) {
    const Planned p = planProduct(config::LayerKind::Maximum, 0);
    auto r = renderer(p);
    ASSERT_TRUE(r);
    int checked = 0, rising = 0;
    for (std::size_t i : samplePosts()) {
        double expected = -1e30;
        walk(i, [&](double, double v, double) { expected = std::max(expected, v); });
        const glm::ivec3 got = drawPost(*r, p, i);
        ASSERT_TRUE(near1(got, lutDn(expected)))
            << text(got) << " vs " << text(lutDn(expected)) << "post " << i << " max " << expected;
        ++checked;
        rising += valueAt(i, kFrame, kAlpha) > mFrames[kFrame][i] + 0.05 &&
                  valueAt(i, kFrame, kAlpha) >= expected;  // the envelope moves on screen
    }
    EXPECT_GT(checked, 100);
    std::printf("maximum: %d posts within 1 DN (%d rising between the frames)\n", checked, rising);
}

TEST_F(ProductsGLTest, DurationAboveThresholdWithinOneDn) {
    const double threshold = 0.3;
    const Planned p = planProduct(config::LayerKind::Duration, threshold);
    auto r = renderer(p);
    ASSERT_TRUE(r);
    int checked = 0, partial = 0;
    for (std::size_t i : samplePosts()) {
        double expected = 0;
        walk(i, [&](double, double v, double dt) { expected += v >= threshold ? dt : 0.0; });
        const glm::ivec3 got = drawPost(*r, p, i);
        ASSERT_TRUE(near1(got, lutDn(expected)))
            << text(got) << " vs " << text(lutDn(expected)) << " post " << i << " " << expected;
        ++checked;
        partial += expected > 0.1 && expected < minutes(kFrame) - 0.1;
    }
    EXPECT_GT(checked, 100);
    EXPECT_GT(partial, 10) << "too few posts with a partial duration to test";
}

TEST_F(ProductsGLTest, ArrivalTimeWithinOneFrameStep) {
    const double threshold = 0.5;
    const Planned p = planProduct(config::LayerKind::Arrival, threshold);
    auto r = renderer(p);
    ASSERT_TRUE(r);
    const double step = minutes(1) - minutes(0);
    int arrived = 0, notYet = 0;
    for (std::size_t i : samplePosts()) {
        double expected = NAN;
        walk(i, [&](double t, double v, double) {
            if (std::isnan(expected) && v >= threshold) expected = t;
        });
        const glm::ivec3 got = drawPost(*r, p, i);
        if (std::isnan(expected)) {
            ASSERT_TRUE(near1(got, glm::ivec3(0, 255, 0)))
                << text(got) << " vs " << text(glm::ivec3(0, 255, 0)) << "post " << i
                << " has not arrived";
            ++notYet;
            continue;
        }
        // Reached within a sub-step of the current time: on screen or not is float rounding.
        if (std::abs(expected - (minutes(kFrame) + kAlpha * step)) < step / 100) continue;
        ASSERT_EQ(got.y, 0) << "post " << i << " arrived at " << expected << " min, not drawn";
        const double shown = double(got.x) / 255.0 * kLutMax;  // the ramp's red channel
        ASSERT_NEAR(shown, expected, step) << "post " << i;
        ++arrived;
    }
    EXPECT_GT(arrived, 50);
    EXPECT_GT(notYet, 10);
}

// The loader's running state resumed after seeks (forwards, far back, forwards again) equals a
// cold computation: the product depends on the frame only, never on the order of requests.
TEST_F(ProductsGLTest, RunningStateAfterSeeksEqualsColdComputation) {
    products::DurationAbove duration(0.3, 60.0, 0.0, false);
    loader::DerivedTiles warm;
    io::RasterTile out;
    for (int f : {5, 40, 12, 41, 17, 30}) {
        Diagnostics d = warm.compute(1, duration, *mReader, "flood", f, mTile, out);
        ASSERT_FALSE(d.hasErrors()) << d.format();
    }
    loader::DerivedTiles cold;
    io::RasterTile fresh;
    ASSERT_FALSE(cold.compute(1, duration, *mReader, "flood", 30, mTile, fresh).hasErrors());
    ASSERT_EQ(out.values.size(), fresh.values.size());
    for (std::size_t i = 0; i < out.values.size(); ++i)
        ASSERT_TRUE(out.values[i] == fresh.values[i] ||
                    (std::isnan(out.values[i]) && std::isnan(fresh.values[i])))
            << "post " << i;
    // A budget too small for two tiles still gives the same values (recomputed from frame 0).
    loader::DerivedTiles tight;
    tight.setBudget(1);
    io::RasterTile again;
    ASSERT_FALSE(tight.compute(1, duration, *mReader, "flood", 30, mTile, again).hasErrors());
    EXPECT_EQ(std::memcmp(again.values.data(), fresh.values.data(), fresh.values.size() * 4), 0);
}

// Two product layers on one tile under a budget below one state (as the 16 MB floor of the CPU
// tile budget was for 3 products x 5 cairns tiles): without the view's tracks every step
// restarts the other layer from frame 0; with them (the scene says how many it draws) each step
// folds one frame per layer, the checkpoint at frame 15 dropped instead. The values are the
// same either way.
TEST_F(ProductsGLTest, StatesOfTheViewAreKeptWhateverTheBudget) {
    products::MaximumSoFar maximum(0.0);
    products::DurationAbove duration(0.3, 60.0, 0.0, false);
    std::uint64_t folded[2] = {0, 0};
    io::RasterTile last[2][2];
    for (int inView = 0; inView < 2; ++inView) {
        loader::DerivedTiles tiles;
        tiles.setBudget(1);
        if (inView) tiles.setTracksInView(2);
        for (int f = 10; f <= 20; ++f) {
            ASSERT_FALSE(tiles.compute(1, maximum, *mReader, "flood", f, mTile, last[inView][0])
                             .hasErrors());
            ASSERT_FALSE(tiles.compute(2, duration, *mReader, "flood", f, mTile, last[inView][1])
                             .hasErrors());
        }
        folded[inView] = tiles.framesFolded();
        // Checkpoints go before latest states: the two latest states and next frames fit.
        if (inView) {
            EXPECT_LE(tiles.bytes(), tiles.budget());
        }
    }
    EXPECT_EQ(folded[1], 2u * 11u + 2u * 10u);  // frames 0..10 once, then one per step
    EXPECT_EQ(folded[0], 2u * (11u + 12u + 13u + 14u + 15u + 16u + 17u + 18u + 19u + 20u + 21u));
    for (int k = 0; k < 2; ++k) {
        ASSERT_EQ(last[0][k].values.size(), last[1][k].values.size());
        EXPECT_EQ(std::memcmp(last[0][k].values.data(), last[1][k].values.data(),
                              last[1][k].values.size() * sizeof(float)),
                  0);
    }
}

// ARR 2019 Book 6 Chapter 7 Table 6.7.4 written out independently: per class the depth (m),
// velocity (m/s) and depth x velocity (m2/s) limits.
int arrClass(double d, double v) {
    if (d <= 0) return 0;
    if (d <= 0.3 && v <= 2.0 && d * v <= 0.3) return 1;
    if (d <= 0.5 && v <= 2.0 && d * v <= 0.6) return 2;
    if (d <= 1.2 && v <= 2.0 && d * v <= 0.6) return 3;
    if (d <= 2.0 && v <= 2.0 && d * v <= 1.0) return 4;
    if (d <= 4.0 && v <= 4.0 && d * v <= 4.0) return 5;
    return 6;
}

TEST(HazardClasses, SyntheticFieldCrossingEveryThreshold) {
    // A 200 x 200 field: depth 0..5 m along x, velocity 0..5 m/s along y, so every depth,
    // velocity and product limit is crossed.
    constexpr int n = 200;
    std::vector<float> depth(n * n), velocity(n * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            depth[std::size_t(y * n + x)] = 5.0f * float(x) / float(n - 1);
            velocity[std::size_t(y * n + x)] = 5.0f * float(y) / float(n - 1);
        }
    std::vector<float> classes = depth;
    products::HazardClass("velocity").combine(classes, velocity);
    std::array<int, 7> seen{};
    for (std::size_t i = 0; i < classes.size(); ++i) {
        const int expected = arrClass(depth[i], velocity[i]);
        const int got = std::isnan(classes[i]) ? 0 : int(classes[i]);
        ASSERT_EQ(got, expected) << "depth " << depth[i] << " velocity " << velocity[i];
        ++seen[std::size_t(got)];
    }
    for (int c = 0; c <= 6; ++c)
        EXPECT_GT(seen[std::size_t(c)], 0) << "class " << c << " never met";
    // Exactly on the limits: the lower class (the table's limits are inclusive).
    EXPECT_EQ(products::HazardCurves::classOf(0.3, 1.0), 1);
    EXPECT_EQ(products::HazardCurves::classOf(0.5, 1.2), 2);
    EXPECT_EQ(products::HazardCurves::classOf(1.2, 0.5), 3);
    EXPECT_EQ(products::HazardCurves::classOf(2.0, 0.5), 4);
    EXPECT_EQ(products::HazardCurves::classOf(4.0, 1.0), 5);
    EXPECT_EQ(products::HazardCurves::classOf(0.1, 4.01), 6);
    // Depth-only fallback: the depth limits alone.
    std::vector<float> byDepth = {0.0f, 0.2f, 0.4f, 1.0f, 1.9f, 3.0f, 4.5f};
    products::HazardClass("").combine(byDepth, {});
    EXPECT_TRUE(std::isnan(byDepth[0]));
    for (int c = 1; c <= 6; ++c) EXPECT_EQ(int(byDepth[std::size_t(c)]), c);
}

}  // namespace
}  // namespace kiosk::layers
