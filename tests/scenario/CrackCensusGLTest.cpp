// Issue 12: no cracks where tiles are refined for texture only. The census of
// ../shared/tools/crack-census.sh (tests/support/CrackCensus.h) over what a user renders: the
// demo's whole camera tour and its `overview` viewpoint at 1280x720, and a real DEM with texture
// layers from eight headings at an oblique pitch. Every frame is drawn the way `render` draws
// it (wait until every tile is resident, then draw terrain and overlays).
#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Session.h"
#include "tests/support/CrackCensus.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/GoldenImage.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;
constexpr int kW = 1280, kH = 720;

class CrackCensus : public test::EglTest {
protected:
    /** Draws `vp` at `time` like `render` (settled), counts crack pixels, keeps failing frames. */
    test::CrackCount census(Session& s, gl::RenderTarget& rt, const math::Viewpoint& vp,
                            double time, const std::string& label) {
        const math::Camera cam =
            makeCamera(vp, s.terrain().bounds(), kW, kH, s.scenario().camera.fovY);
        rt.bind();
        EXPECT_TRUE(test::settleView(s, cam, time)) << label << ": tiles still loading";
        s.drawFrame(cam, time, kW, kH);
        const gl::Image img = rt.readColor();
        const test::CrackCount c = test::crackPixels(img);
        if (c.cracks) {
            const char* root = std::getenv("KIOSK_TEST_OUTPUT");
            const fs::path out =
                fs::path(root && *root ? root : "build/golden-out") / ("cracks-" + label + ".png");
            fs::create_directories(out.parent_path());
            test::writeImage(out.string(), img);
        }
        EXPECT_EQ(c.cracks, 0) << label << ": " << c.cracks << " crack pixels, first at ("
                               << c.firstX << ", " << c.firstY << "); frame written to golden-out/";
        return c;
    }

    std::unique_ptr<Session> openDemo() {
        auto s = Session::open("scenarios/demo/rainier.json", mCaps);
        EXPECT_TRUE(s.ok()) << s.diagnostics.format();
        return s ? std::move(*s.value) : nullptr;
    }

    /** The tour as `render --from +0 --to +9h --fps 1` renders it, frames [first, last). */
    void tour(std::int64_t first, std::int64_t last) {
        if (!fs::exists("data/generated/rainier.gpkg"))
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA",
                               "demo store missing: run tools/prepare-demo.sh");
        auto rt = gl::RenderTarget::create(kW, kH);
        ASSERT_TRUE(rt.ok());
        auto s = openDemo();
        ASSERT_TRUE(s);
        const double t0 = s->startTime(), t1 = s->startTime() + 9 * 3600.0;
        const double rate = std::fabs(s->scenario().clock->rate);
        const std::int64_t n = anim::frameCount(t0, t1, 1.0, rate);
        ASSERT_GE(n, last) << "the tour got shorter: the test no longer covers it";
        scene::Playback playback;
        playback.rate = rate;
        playback.start = t0;
        playback.end = t1;
        s->setPlayback(playback);
        int sky = 0;
        for (std::int64_t i = first; i < std::min(last, n); ++i) {
            const double t = anim::timeForFrame(t0, t1, 1.0, i, rate);
            auto vp = s->viewpointAt(t, "");
            ASSERT_TRUE(vp.ok());
            sky += census(*s, *rt, *vp, t, "tour-" + std::to_string(i + 1)).sky;
        }
        // The method needs background to flood from; without it every count would be 0.
        EXPECT_GT(sky, 0) << "no clear-colour pixel at all: did the clear colour change?";
    }
};

// The census itself, on a drawn picture: sky around a terrain block with a 3-pixel crack and
// a 2x2 hole inside, a panel (enclosed by terrain, clear colour inside its box is not a crack)
// and the progress band.
TEST(CrackCensusMethod, CountsOnlyClearColourEnclosedByTerrain) {
    gl::Image img;
    img.width = 200;
    img.height = 120;
    img.rgba.assign(std::size_t(img.width * img.height) * 4, 255);
    auto paint = [&](int x0, int y0, int x1, int y1, std::uint8_t r, std::uint8_t g,
                     std::uint8_t b) {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                std::uint8_t* p = img.pixel(x, y);
                p[0] = r, p[1] = g, p[2] = b;
            }
    };
    paint(0, 0, 200, 120, 159, 180, 205);    // sky, within +-2 of the clear colour
    paint(20, 20, 180, 100, 90, 110, 60);    // terrain
    paint(50, 40, 53, 41, 158, 181, 204);    // a crack: 3 px
    paint(100, 60, 102, 62, 157, 182, 203);  // a hole: 4 px
    paint(120, 30, 150, 50, 53, 63, 76);     // a panel over the terrain ...
    paint(130, 35, 140, 40, 158, 181, 204);  // ... with clear colour inside its box
    paint(20, 108, 180, 116, 90, 110, 60);   // terrain through the progress band ...
    paint(60, 110, 62, 112, 158, 181, 204);  // ... where clear colour is not a crack
    const test::CrackCount c = test::crackPixels(img);
    EXPECT_EQ(c.cracks, 7);
    EXPECT_EQ(c.firstX, 50);
    EXPECT_EQ(c.firstY, 40);
    EXPECT_EQ(c.sky, 200 * 120 - 160 * 80 - 160 * 8 + 3 + 4 + 50 + 4);
}

// The tour is 28 frames at fps 1 (9 h at 1200x); the cracks were in frames 1-5 and 22-28
// (fps 2: 1-10 and 43-55). Two halves keep each test short.
TEST_F(CrackCensus, DemoTourFirstHalf) {
    tour(0, 14);
}
TEST_F(CrackCensus, DemoTourSecondHalf) {
    tour(14, 28);
}

TEST_F(CrackCensus, DemoOverviewAtSeveralTimes) {
    if (!fs::exists("data/generated/rainier.gpkg"))
        KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA", "demo store missing: run tools/prepare-demo.sh");
    auto rt = gl::RenderTarget::create(kW, kH);
    ASSERT_TRUE(rt.ok());
    auto s = openDemo();
    ASSERT_TRUE(s);
    for (int h : {0, 2, 5, 9}) {
        const double t = s->startTime() + h * 3600.0;
        auto vp = s->viewpointAt(t, "overview");
        ASSERT_TRUE(vp.ok());
        census(*s, *rt, *vp, t, "overview-" + std::to_string(h) + "h");
    }
}

// Puget Sound (the seed paper's data set, 160 m posts) with the demo's texture layers: an
// elevation transfer function, a hillshade and a normal map, so that tiles are refined for
// texture beyond their geometry. Eight headings (the cracks were at headings looking west or
// north) at an oblique pitch, four per test; the store is imported once for both.
class RealDemCracks : public CrackCensus {
protected:
    static void SetUpTestSuite() {
        const std::string puget = test::sharedData("puget_sound_heightmap/ps_height_1k.png");
        if (puget.empty()) return;
        sDir = fs::temp_directory_path() / ("kiosk-cracks-" + std::to_string(::getpid()));
        fs::create_directories(sDir);
        const std::string bin = KIOSK_GEOKIOSK_BIN, store = (sDir / "puget.gpkg").string();
        for (const std::string& args :
             {"import elevation '" + puget + "' --store '" + store +
                  "' --pixel-size 160 --z-scale 0.1",
              "import topographic --store '" + store + "' --name hillshade",
              "import topographic --normals --store '" + store + "' --name normals"})
            if (std::system(("'" + bin + "' " + args + " --quiet").c_str()) != 0)
                sImportError = "geokiosk " + args + " failed";
        std::ofstream(sDir / "puget.json") << R"({ "version": 1, "title": "Puget Sound",
            "stores": { "p": "puget.gpkg" },
            "terrain": { "store": "p", "tauGeom": 2, "tauTex": 1 },
            "transferFunctions": { "relief": { "space": "lab", "stops": [
                { "value": 0, "color": "#3f7f4f" }, { "value": 2000, "color": "#c9b98a" },
                { "value": 4400, "color": "#ffffff" } ] } },
            "layers": [
              { "id": "relief", "kind": "data", "source": { "store": "p", "layer": "elevation" },
                "transfer": "relief" },
              { "id": "hill", "kind": "topographic", "source": { "store": "p", "layer": "hillshade" },
                "operation": "modulate" },
              { "id": "shade", "kind": "normals", "source": { "store": "p", "layer": "normals" },
                "operation": "modulate" } ] })";
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        if (!sDir.empty()) fs::remove_all(sDir, ec);
    }

    void headings(int first) {
        if (sDir.empty()) KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA", "../shared/data not present");
        ASSERT_EQ(sImportError, "");
        auto rt = gl::RenderTarget::create(kW, kH);
        ASSERT_TRUE(rt.ok());
        auto s = Session::open(sDir / "puget.json", mCaps);
        ASSERT_TRUE(s.ok()) << s.diagnostics.format();
        const glm::dvec3 c = (*s)->terrain().bounds().center();
        int sky = 0;
        for (int k = first; k < first + 4; ++k) {
            const math::Viewpoint vp{glm::dvec3(c.x, c.y, 100), 45.0 * k, -25, 70000};
            sky +=
                census(**s, *rt, vp, (*s)->startTime(), "puget-heading-" + std::to_string(45 * k))
                    .sky;
        }
        EXPECT_GT(sky, 0) << "no sky in any view: the views do not reach the horizon";
    }

    static inline fs::path sDir;
    static inline std::string sImportError;
};

TEST_F(RealDemCracks, HeadingsNorthToSouthEast) {
    headings(0);
}
TEST_F(RealDemCracks, HeadingsSouthToNorthWest) {
    headings(4);
}

}  // namespace
}  // namespace kiosk::app
