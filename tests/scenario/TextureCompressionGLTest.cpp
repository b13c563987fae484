// GPU texture compression in the running scene (issue 20, docs/terrain.md §11): the demo store
// with ASTC 4x4 blocks from `import textures`, rendered on llvmpipe with the blocks uploaded
// (terrain.textureCompression "astc") and without ("off"), pixels read back. The compressed
// picture stays within the texture error bound; data layers are bit-exact; a store without
// blocks and damaged block rows fall back to the PNG tiles.
#include "runtime/app/Session.h"
#include "runtime/core/Log.h"
#include "runtime/import/TextureCompression.h"
#include "runtime/io/SqliteDb.h"
#include "tests/support/DemoStoreTest.h"
#include "tests/support/GoldenImage.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <set>
#include <string>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;
using config::TextureCompression;

constexpr int kW = 480, kH = 270;

struct Rendered {
    gl::Image image;
    scene::TextureChoice choice;
    scene::SceneCacheUsage usage;
};

/** Colour agreement of two renders of one view (RGB). */
struct Agreement {
    double psnrDb = 99;
    int maxError = 0;
    /** Pixels whose error exceeds what moving the texture by tauTex pixels already changes. */
    std::size_t beyondBound = 0;
    std::size_t pixels = 0;
};

/**
 * The τ_tex colour bound: the selector lets a texel cover up to tauTex pixels, so the
 * uncompressed picture is itself only known to within a displacement of tauTex pixels. A
 * compressed pixel is within the bound when its error is no larger than the largest change
 * between the uncompressed pixel and its neighbours within tauTex pixels (plus one level of
 * rounding), per channel.
 */
Agreement agreement(const gl::Image& ref, const gl::Image& test, int tauTexPx) {
    Agreement a;
    double se = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            const std::uint8_t* r = ref.pixel(x, y);
            const std::uint8_t* t = test.pixel(x, y);
            bool beyond = false;
            for (int c = 0; c < 3; ++c) {
                const int e = std::abs(int(r[c]) - int(t[c]));
                se += double(e) * e;
                a.maxError = std::max(a.maxError, e);
                int local = 0;
                for (int dy = -tauTexPx; dy <= tauTexPx; ++dy)
                    for (int dx = -tauTexPx; dx <= tauTexPx; ++dx) {
                        const int nx = std::clamp(x + dx, 0, ref.width - 1);
                        const int ny = std::clamp(y + dy, 0, ref.height - 1);
                        local = std::max(local, std::abs(int(ref.pixel(nx, ny)[c]) - int(r[c])));
                    }
                beyond |= e > local + 1;
            }
            a.beyondBound += beyond ? 1u : 0u;
            ++a.pixels;
        }
    const double mse = se / double(a.pixels * 3);
    a.psnrDb = mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 99.0;
    return a;
}

class TextureCompressionGL : public test::DemoStoreTest {
protected:
    static void SetUpTestSuite() {
        if (!fs::exists("data/generated/rainier.gpkg")) return;
        sDir = fs::temp_directory_path() / ("geokiosk-texcomp-" + std::to_string(::getpid()));
        fs::remove_all(sDir);
        fs::create_directories(sDir);
        sStore = sDir / "rainier-astc.gpkg";
        fs::copy_file("data/generated/rainier.gpkg", sStore);
        import::TextureImportOptions o;
        o.store = sStore;
        o.quiet = true;
        o.layers = {"normals"};  // the layer the demo draws; default quality
        auto r = import::importTextureBlocks(o);
        sImport = r.diagnostics.format();
        if (r.ok()) sReports = *r;
        ::setenv("GEOKIOSK_ALLOW_PATHS", sDir.c_str(), 1);
    }
    static void TearDownTestSuite() {
        ::unsetenv("GEOKIOSK_ALLOW_PATHS");
        if (!sDir.empty()) fs::remove_all(sDir);
    }
    void SetUp() override {
        DemoStoreTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        ASSERT_FALSE(sReports.empty()) << sImport;
    }

    Rendered render(const fs::path& store, TextureCompression mode, const std::string& viewpoint,
                    const std::function<void(config::Scenario&)>& more = nullptr) {
        Rendered out;
        auto rt = gl::RenderTarget::create(kW, kH);
        EXPECT_TRUE(rt.ok());
        if (!rt.ok()) return out;
        auto s = Session::open("scenarios/demo/rainier.json", mCaps, [&](config::Scenario& sc) {
            sc.stores.at("rainier").path = store;
            sc.terrain.textureCompression = mode;
            if (more) more(sc);
        });
        EXPECT_TRUE(s.ok()) << s.diagnostics.format();
        if (!s.ok()) return out;
        Session& session = **s;
        auto vp = session.viewpointAt(session.startTime(), viewpoint);
        EXPECT_TRUE(vp.ok());
        const math::Camera cam = makeCamera(*vp, session.terrain().bounds(), kW, kH, 45);
        const double t = session.startTime() + 3 * 3600;
        EXPECT_TRUE(test::settleView(session, cam, t));
        rt->bind();
        session.drawFrame(cam, t, kW, kH);
        out.image = rt->readColor();
        out.choice = session.terrain().textureChoice();
        out.usage = session.terrain().cacheUsage();
        return out;
    }

    static fs::path sDir, sStore;
    static std::string sImport;
    static std::vector<import::TextureLayerReport> sReports;
};

fs::path TextureCompressionGL::sDir, TextureCompressionGL::sStore;
std::string TextureCompressionGL::sImport;
std::vector<import::TextureLayerReport> TextureCompressionGL::sReports;

bool identical(const gl::Image& a, const gl::Image& b) {
    return a.width == b.width && a.height == b.height && a.rgba == b.rgba;
}

TEST(TextureChoiceTest, FollowsTheSettingTheContextAndTheRenderer) {
    gl::Caps gpu;
    gpu.renderer = "Mali-G610";
    gpu.extensions = "GL_EXT_foo GL_KHR_texture_compression_astc_ldr GL_OES_bar";
    gl::Caps soft = gpu;
    soft.renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
    gl::Caps none;
    none.renderer = "V3D 4.2";
    none.extensions = "GL_KHR_texture_compression_astc_hdr_x";
    using F = io::TextureFormat;
    EXPECT_EQ(scene::chooseTextureFormat(TextureCompression::Auto, gpu).format, F::Astc4x4);
    EXPECT_EQ(scene::chooseTextureFormat(TextureCompression::Auto, soft).format, F::None);
    EXPECT_TRUE(scene::chooseTextureFormat(TextureCompression::Auto, soft).software);
    EXPECT_EQ(scene::chooseTextureFormat(TextureCompression::Astc, soft).format, F::Astc4x4);
    EXPECT_EQ(scene::chooseTextureFormat(TextureCompression::Off, gpu).format, F::None);
    EXPECT_EQ(scene::chooseTextureFormat(TextureCompression::Astc, none).format, F::None);
    EXPECT_EQ(scene::chooseTextureFormat(TextureCompression::Auto, none).format, F::None);
    // What a software renderer holds: the blocks and the RGBA8 it expands them to.
    io::CompressedImage img{{}, F::Astc4x4, 256, 256, 9, std::vector<std::uint8_t>(87408)};
    EXPECT_EQ(scene::compressedTextureBytes(img, false), 87408u);
    EXPECT_EQ(scene::compressedTextureBytes(img, true), 87408u + 349524u);
}

TEST_F(TextureCompressionGL, CompressedRenderStaysWithinTheTextureBound) {
    for (const auto& r : sReports)
        RecordProperty("import_psnr_min_db_" + r.layer, std::to_string(r.psnrMinDb));
    for (const char* view : {"overview", "summit"}) {
        SCOPED_TRACE(view);
        const Rendered off = render(sStore, TextureCompression::Off, view);
        const Rendered astc = render(sStore, TextureCompression::Astc, view);
        ASSERT_FALSE(off.image.rgba.empty());
        ASSERT_FALSE(astc.image.rgba.empty());
        if (astc.choice.format != io::TextureFormat::Astc4x4)
            GTEST_SKIP() << "this context has no ASTC LDR: " << astc.choice.reason;
        EXPECT_EQ(off.choice.format, io::TextureFormat::None);
        // The shading layer's tiles went up as blocks; none without compression.
        EXPECT_GT(astc.usage.gpuTexturesCompressed, 0u);
        EXPECT_EQ(off.usage.gpuTexturesCompressed, 0u);
        EXPECT_FALSE(identical(off.image, astc.image)) << "the blocks were drawn";
        const Agreement a = agreement(off.image, astc.image, 1);  // the demo's tauTex = 1
        RecordProperty(std::string("psnr_db_") + view, std::to_string(a.psnrDb));
        RecordProperty(std::string("max_error_") + view, a.maxError);
        RecordProperty(std::string("beyond_bound_") + view, int(a.beyondBound));
        std::printf("%s: PSNR %.2f dB, max error %d, %zu of %zu pixels beyond the tauTex bound\n",
                    view, a.psnrDb, a.maxError, a.beyondBound, a.pixels);
        EXPECT_GE(a.psnrDb, 40.0);
        EXPECT_LE(a.beyondBound, a.pixels / 1000) << "at most 0.1 % of the pixels";
        if (HasFailure())
            for (const auto& [name, img] : {std::pair{"off", &off.image}, {"astc", &astc.image}})
                test::writeImage(
                    (sDir.parent_path() / ("texcomp-" + std::string(view) + "-" + name + ".png"))
                        .string(),
                    *img);
    }
}

TEST_F(TextureCompressionGL, DataLayersStayBitExact) {
    // The demo's data layers alone (relief through its LUT, the flood sequence): the store's
    // imagery blocks change nothing, and nothing is uploaded compressed.
    auto dataOnly = [](config::Scenario& sc) {
        for (auto& l : sc.layers)
            if (l.kind == config::LayerKind::Normals) l.enabled = false;
    };
    for (const char* view : {"overview", "summit"}) {
        SCOPED_TRACE(view);
        const Rendered off = render(sStore, TextureCompression::Off, view, dataOnly);
        const Rendered astc = render(sStore, TextureCompression::Astc, view, dataOnly);
        ASSERT_FALSE(off.image.rgba.empty());
        EXPECT_TRUE(identical(off.image, astc.image));
        EXPECT_EQ(astc.usage.gpuTexturesCompressed, 0u);
        EXPECT_GT(astc.usage.gpuTextures, 0u) << "the data layers' textures are resident";
    }
}

TEST_F(TextureCompressionGL, StoreWithoutBlocksRendersUncompressed) {
    const Rendered off = render("data/generated/rainier.gpkg", TextureCompression::Off, "summit");
    const Rendered astc =
        render(fs::absolute("data/generated/rainier.gpkg"), TextureCompression::Astc, "summit");
    ASSERT_FALSE(off.image.rgba.empty());
    EXPECT_TRUE(identical(off.image, astc.image));
    EXPECT_EQ(astc.usage.gpuTexturesCompressed, 0u);
}

TEST_F(TextureCompressionGL, DamagedBlockRowsFallBackWithOneLineEach) {
    const fs::path damaged = sDir / "rainier-damaged.gpkg";
    fs::copy_file(sStore, damaged, fs::copy_options::overwrite_existing);
    {
        auto db = io::SqliteDb::open(damaged, io::SqliteDb::Mode::ReadWrite);
        ASSERT_TRUE(db.ok());
        // Every row of the shading layer short, some with a level count that cannot be.
        ASSERT_FALSE(db->exec("UPDATE kiosk_tile_textures SET blocks = substr(blocks, 1, 1000) "
                              "WHERE table_name = 'normals'; UPDATE kiosk_tile_textures SET "
                              "levels = 99 WHERE table_name = 'normals' AND zoom_level = 2")
                         .hasErrors());
    }
    const Rendered off = render(damaged, TextureCompression::Off, "summit");
    const Rendered astc = render(damaged, TextureCompression::Astc, "summit");
    ASSERT_FALSE(astc.image.rgba.empty());
    EXPECT_TRUE(identical(off.image, astc.image)) << "every tile drawn from its PNG";
    EXPECT_EQ(astc.usage.gpuTexturesCompressed, 0u);
    // One line per damaged tile loaded, naming it; never the same tile twice.
    std::set<std::string> named;
    int lines = 0;
    for (const std::string& line : log::recent(400)) {
        if (line.find("STORE_TEXTURE_CORRUPT") == std::string::npos) continue;
        ++lines;
        EXPECT_NE(line.find("PNG tile drawn instead"), std::string::npos) << line;
        const std::size_t at = line.find("normals/");
        ASSERT_NE(at, std::string::npos) << line;
        named.insert(line.substr(at, line.find_first_of(": ", at) - at));
    }
    EXPECT_GT(lines, 0);
    EXPECT_EQ(std::size_t(lines), named.size());
}

}  // namespace
}  // namespace kiosk::app
