// Class (fire) sequences with interpolate "arrival" through the whole scene (issue 6): the
// loader computes each frame pair's per-pixel thresholds, the shader switches each pixel when
// alpha passes its threshold, so between two frames the burn front lies between the old and
// the new perimeter at the fraction alpha, and burned/unburned are never blended.
#include "runtime/app/Session.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/SettleView.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;

constexpr int kPosts = 256;                // 10 m posts: a 2.56 km square
constexpr int kFront[3] = {64, 192, 240};  // burned columns (x < front) per frame
constexpr int kView = 200;

class FireArrival : public test::EglTest {
protected:
    static void SetUpTestSuite() {
        sDir = fs::temp_directory_path() / ("kiosk-fire-" + std::to_string(::getpid()));
        fs::create_directories(sDir);
        GDALAllRegister();
        double geo[6] = {500000.0, 10.0, 0.0, 4000000.0, 0.0, -10.0};
        OGRSpatialReference srs;
        srs.importFromEPSG(32610);
        auto write = [&](const fs::path& f, const std::function<float(int, int)>& v) {
            GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(
                f.c_str(), kPosts, kPosts, 1, GDT_Float32, nullptr);
            ds->SetGeoTransform(geo);
            ds->SetSpatialRef(&srs);
            std::vector<float> z(std::size_t(kPosts) * kPosts);
            for (int y = 0; y < kPosts; ++y)
                for (int x = 0; x < kPosts; ++x)
                    z[std::size_t(y) * kPosts + std::size_t(x)] = v(x, y);
            const bool ok =
                ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, kPosts, kPosts, z.data(), kPosts,
                                               kPosts, GDT_Float32, 0, 0) == CE_None;
            GDALClose(ds);
            if (!ok) sImport = "cannot write " + f.string();
        };
        write(sDir / "dem.tif", [](int x, int) { return 300.0f + 0.01f * float(x); });
        import::ImportOptions o;
        o.store = sDir / "fire.gpkg";
        o.quiet = true;
        o.name = "elevation";
        if (sImport.empty())
            sImport = import::importElevation((sDir / "dem.tif").string(), o).format();
        std::vector<std::string> frames;
        std::ofstream csv(sDir / "times.csv");
        for (int k = 0; k < 3; ++k) {
            const fs::path f = sDir / ("burn_" + std::to_string(k) + ".tif");
            write(f, [k](int x, int) { return x < kFront[k] ? 1.0f : 0.0f; });
            csv << f.filename().string() << ",2026-03-14T0" << k << ":00:00Z\n";
            frames.push_back(f.string());
        }
        csv.close();
        o.name = "burn";
        o.timesCsv = (sDir / "times.csv").string();
        o.categorical = true;
        if (sImport.empty()) sImport = import::importSequence(frames, o).format();
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(sDir, ec);
    }

    std::unique_ptr<Session> open(const std::string& interpolate) {
        EXPECT_EQ(sImport, "");
        const fs::path p = sDir / ("fire-" + interpolate + ".json");
        std::ofstream(p) << R"({ "version": 1, "title": "", "stores": { "s": "fire.gpkg" },
            "terrain": { "store": "s", "tauGeom": 1, "tauTex": 1 },
            "transferFunctions": { "burn": { "units": "class", "stops": [
                { "value": 0, "color": "#00ff00" }, { "value": 1, "color": "#ff0000" } ] } },
            "layers": [ { "id": "fire", "kind": "sequence", "source": { "store": "s", "sequence": "burn" },
                          "transfer": "burn", "interpolate": ")"
                         << interpolate << R"(" } ] })";
        auto s = Session::open(p, mCaps);
        EXPECT_TRUE(s.ok()) << s.diagnostics.format();
        return s ? std::move(*s.value) : nullptr;
    }

    struct Counts {
        int burned = 0, unburned = 0, blended = 0;
        double burnedFraction() const { return double(burned) / std::max(1, burned + unburned); }
    };

    /** Draw at `time` once every tile is resident; classify the terrain pixels by hue. */
    Counts draw(Session& s, gl::RenderTarget& rt, double time) {
        math::Viewpoint vp;
        vp.target = glm::dvec3(500000.0 + 1280.0, 4000000.0 - 1280.0, 300.0);
        vp.headingDeg = 0;
        vp.pitchDeg = -89.9;
        vp.range = 2400;  // the middle ~1.9 km: no sky, no skirts in view
        return draw(s, rt, time, vp);
    }
    Counts draw(Session& s, gl::RenderTarget& rt, double time, const math::Viewpoint& vp) {
        const math::Camera cam = makeCamera(vp, s.terrain().bounds(), kView, kView, 45.0);
        test::settleView(s, cam, time);
        rt.bind();
        s.drawFrame(cam, time, kView, kView);
        const gl::Image img = rt.readColor();
        Counts c;
        for (int y = 0; y < kView; ++y)
            for (int x = 0; x < kView; ++x) {
                const auto* p = img.pixel(x, y);
                const int r = p[0], g = p[1];
                if (r > 3 * g + 10)
                    ++c.burned;
                else if (g > 3 * r + 10)
                    ++c.unburned;
                else
                    ++c.blended;
            }
        return c;
    }

    static inline fs::path sDir;
    static inline std::string sImport;
};

TEST_F(FireArrival, FrontSweepsBetweenPerimetersWithoutBlending) {
    auto s = open("arrival");
    ASSERT_TRUE(s);
    auto rt = makeTarget(kView, kView);
    const double t0 = s->startTime();
    // The view spans columns 32..224 of the 256 (range 2400 m at 45 deg: ~1.99 km wide).
    auto expected = [](double frontColumn) {
        const double lo = 128.0 - 99.4, hi = 128.0 + 99.4;
        return std::clamp((frontColumn - lo) / (hi - lo), 0.0, 1.0);
    };
    double previous = -1;
    for (double alpha : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        const Counts c = draw(*s, rt, t0 + 3600.0 * alpha);
        const double front = kFront[0] + alpha * (kFront[1] - kFront[0]);
        EXPECT_NEAR(c.burnedFraction(), expected(front), 0.04) << "alpha " << alpha;
        // One column of filtered texels along the front at most (the class texture is
        // bilinear): never a band of blended classes.
        EXPECT_LE(c.blended, 3 * kView) << "alpha " << alpha;
        EXPECT_GT(c.burnedFraction(), previous) << "the front did not advance at alpha " << alpha;
        previous = c.burnedFraction();
    }
}

TEST_F(FireArrival, ClassDataWithoutArrivalSwitchesAtTheNextFrame) {
    // The contrast that makes the test above meaningful: class data is never mixed, so without
    // "arrival" the front stays on the old perimeter until the next frame's time.
    auto s = open("data");
    ASSERT_TRUE(s);
    auto rt = makeTarget(kView, kView);
    const Counts atFrame = draw(*s, rt, s->startTime());
    const Counts between = draw(*s, rt, s->startTime() + 2700.0);
    const Counts next = draw(*s, rt, s->startTime() + 3600.0);
    EXPECT_NEAR(between.burnedFraction(), atFrame.burnedFraction(), 0.01);
    EXPECT_GT(next.burnedFraction(), atFrame.burnedFraction() + 0.5);
    EXPECT_LE(between.blended, 3 * kView);
}

// The real Cell2Fire Harvest40x40 burn grids (16 hourly frames of a 4 km square): between two
// frames the burned area grows monotonically with alpha, from one frame's scar to the next.
TEST_F(FireArrival, Cell2FireScarGrowsBetweenFrames) {
    const std::string grids = test::sharedData("cell2fire_fire_spread/Harvest40x40/Grids/Grids1");
    const std::string forest = test::sharedData("cell2fire_fire_spread/Harvest40x40/Forest.asc");
    if (grids.empty() || forest.empty())
        GTEST_SKIP() << "../shared/data/cell2fire_fire_spread absent";
    import::ImportOptions o;
    o.store = sDir / "c2f.gpkg";
    o.quiet = true;
    o.name = "elevation";
    o.zScale = 0.001;  // fuel codes as a (nearly flat) terrain: only the scar matters here
    const Diagnostics elevation = import::importElevation(forest, o);  // warns: no CRS
    ASSERT_FALSE(elevation.hasErrors()) << elevation.format();
    o.name = "burn";
    o.zScale = 1.0;
    o.start = *parseIso8601("2026-03-14T00:00:00Z");
    ASSERT_FALSE(import::importSequence({grids}, o).hasErrors());
    const fs::path p = sDir / "c2f.json";
    std::ofstream(p) << R"({ "version": 1, "title": "", "stores": { "s": "c2f.gpkg" },
        "terrain": { "store": "s", "tauGeom": 1, "tauTex": 1 },
        "transferFunctions": { "burn": { "units": "class", "stops": [
            { "value": -1, "color": "#00ff00" }, { "value": 0, "color": "#00ff00" }, { "value": 1, "color": "#ff0000" } ] } },
        "layers": [ { "id": "fire", "kind": "sequence", "source": { "store": "s", "sequence": "burn" },
                      "transfer": "burn", "interpolate": "arrival" } ] })";
    auto opened = Session::open(p, mCaps);
    ASSERT_TRUE(opened.ok()) << opened.diagnostics.format();
    Session& s = **opened;
    auto rt = makeTarget(kView, kView);
    math::Viewpoint vp;
    vp.target = glm::dvec3(457900.0 + 2000.0, 5716800.0 + 2000.0, 0.0);
    vp.headingDeg = 0;
    vp.pitchDeg = -89.9;
    vp.range = 4500;  // ~3.7 km of the 4 km square
    // Frames 3 -> 4 (61 -> 85 burned cells in the grids).
    const double t3 = s.startTime() + 3 * 3600.0;
    double previous = -1;
    std::vector<double> fractions;
    for (double alpha : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        const Counts c = draw(s, rt, t3 + alpha * 3600.0, vp);
        fractions.push_back(c.burnedFraction());
        EXPECT_GE(c.burnedFraction(), previous) << "the scar shrank at alpha " << alpha;
        previous = c.burnedFraction();
    }
    // Strictly between the two frames' scars a quarter into the interval: a sweep, not a
    // switch at either end. (New cells of a 100 m grid mostly touch the old scar, threshold
    // 1 / (1 + 1): most have switched by alpha 0.5.)
    EXPECT_GT(fractions[1], fractions[0] + 0.1 * (fractions[4] - fractions[0]));
    EXPECT_LT(fractions[1], fractions[4] - 0.1 * (fractions[4] - fractions[0]));
    EXPECT_GT(fractions[4], fractions[0] * 1.2) << "frames 3 and 4 should differ by 24 cells";
}

}  // namespace
}  // namespace kiosk::app
