// Crack-freedom as a property of the grid, not of chosen views: the census of
// ../shared/tools/crack-census.sh (tests/support/CrackCensus.h) over generated grids. Each grid
// is written as a user's GeoTIFFs (posts of aspect 0.5 to 2 in degrees on EPSG:4326, or in
// metres on UTM; odd sizes; a notch of nodata), imported as a user would (elevation, a drape at
// twice the resolution so tiles refine for texture beyond the finest mesh, a two-frame
// sequence), and drawn from eight headings at two pitches at 640x360, settled like `render`.
#include "runtime/app/Session.h"
#include "tests/support/CrackCensus.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/FloatTiff.h"
#include "tests/support/GoldenImage.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;
constexpr int kW = 640, kH = 360;

struct GridCase {
    const char* name;
    int epsg;   ///< 4326: posts in degrees (imported into its UTM zone); 32610: metres
    double px;  ///< post spacing east-west, in the CRS's unit
    double py;  ///< post spacing north-south
    int width, height;
};

// About 20 km of ground each, so the views below see similar levels on every grid.
const GridCase kCases[] = {
    {"Degrees_0_5", 4326, 0.000135, 0.00027, 523, 371},
    {"Degrees_1_45", 4326, 0.000279, 0.000193, 701, 519},
    {"Degrees_2", 4326, 0.0004, 0.0002, 467, 601},
    {"Metres_0_5", 32610, 15.0, 30.0, 1201, 611},
    {"Metres_2", 32610, 40.0, 20.0, 517, 1003},
};

/**
 * Heights over the grid's unit square (u east, v south), NaN for nodata: a notch cut from the
 * west edge across tile borders. (A hole enclosed by terrain shows sky the census would count:
 * the notch's sky joins the background.)
 */
double height(double u, double v) {
    if (v > 0.6 && v < 0.69 && u < 0.25 + 0.2 * (v - 0.6)) return std::nan("");
    return 900 + 700 * std::sin(6.3 * u + 1) * std::cos(5.1 * v) +
           300 * std::sin(17 * u) * std::sin(13 * v + 0.5) +
           1200 * std::exp(-((u - 0.5) * (u - 0.5) + (v - 0.5) * (v - 0.5)) * 8);
}

class GridCensus : public test::EglTest, public ::testing::WithParamInterface<GridCase> {
protected:
    /** The grid's GeoTIFFs and store; the scenario over it. "" or what went wrong. */
    std::string makeStore(const fs::path& dir) {
        const GridCase& g = GetParam();
        const double west = g.epsg == 4326 ? -121.9 : 583000.0;
        const double north = g.epsg == 4326 ? 46.95 : 5200000.0;
        test::RasterSpec dem;
        dem.width = g.width;
        dem.height = g.height;
        const double gt[6] = {west, g.px, 0, north, 0, -g.py};
        std::copy(gt, gt + 6, dem.geoTransform);
        dem.epsg = g.epsg;
        dem.nodata = true;
        auto z = [&](int x, int y) { return height(double(x) / g.width, double(y) / g.height); };
        std::string err = test::writeRasterTiff((dir / "dem.tif").string(), dem,
                                                [&](int, int x, int y) { return z(x, y); });
        // The drape at twice the resolution, in colours far from the clear colour the census
        // looks for (a drape pixel that happened to match would count as a crack).
        test::RasterSpec drape = dem;
        drape.width = 2 * g.width;
        drape.height = 2 * g.height;
        drape.geoTransform[1] = g.px / 2;
        drape.geoTransform[5] = -g.py / 2;
        drape.bands = 3;
        drape.nodata = false;
        if (err.empty())
            err =
                test::writeRasterTiff((dir / "drape.tif").string(), drape, [](int b, int x, int y) {
                    return b == 0 ? 60 + (x * 7) % 150 : b == 1 ? 90 + (y * 5) % 150 : (x + y) % 40;
                });
        test::RasterSpec frame = dem;
        frame.nodata = false;
        for (int k = 0; k < 2 && err.empty(); ++k)
            err = test::writeRasterTiff(
                (dir / ("depth" + std::to_string(k) + ".tif")).string(), frame,
                [&](int, int x, int y) {
                    const double h = z(x, y);
                    return std::isnan(h) ? 0.0 : std::max(0.0, (1400 - h) / 200 + 0.5 * k);
                });
        if (!err.empty()) return err;
        std::ofstream(dir / "times.csv") << "time\n2026-01-01T00:00:00Z\n2026-01-01T01:00:00Z\n";
        const std::string bin = KIOSK_GEOKIOSK_BIN, store = (dir / "grid.gpkg").string(),
                          d = dir.string();
        for (const std::string& args :
             {"import elevation '" + d + "/dem.tif' --store '" + store + "'",
              "import imagery '" + d + "/drape.tif' --store '" + store + "' --name drape",
              "import sequence '" + d + "/depth0.tif' '" + d + "/depth1.tif' --store '" + store +
                  "' --name depth --times '" + d + "/times.csv'"})
            if (std::system(("'" + bin + "' " + args + " --quiet").c_str()) != 0)
                return "geokiosk " + args + " failed";
        std::ofstream(dir / "grid.json") << R"({ "version": 1, "title": "",
            "stores": { "g": "grid.gpkg" },
            "terrain": { "store": "g", "tauGeom": 1, "tauTex": 1 },
            "transferFunctions": { "depth": { "space": "lab",
                "stops": [ { "value": 0, "color": "#08306b" }, { "value": 8, "color": "#041f4a" } ],
                "opacity": [ { "value": 0.0, "opacity": 0.0 }, { "value": 0.3, "opacity": 0.9 } ],
                "nodata": "transparent" } },
            "layers": [
              { "id": "drape", "kind": "thematic", "source": { "store": "g", "layer": "drape" } },
              { "id": "flood", "kind": "sequence", "source": { "store": "g", "sequence": "depth" },
                "transfer": "depth", "interpolate": "data", "nodataAs": 0 } ],
            "clock": { "start": "2026-01-01T00:00:00Z", "end": "2026-01-01T01:00:00Z",
                       "rate": 600, "range": "clamp" } })";
        return "";
    }

    void TearDown() override {
        std::error_code ec;
        if (!mDir.empty()) fs::remove_all(mDir, ec);
        test::EglTest::TearDown();
    }

    fs::path mDir;
};

TEST_P(GridCensus, NoCrackFromAnyHeadingAtTwoPitches) {
    mDir = fs::temp_directory_path() /
           ("kiosk-grid-census-" + std::to_string(::getpid()) + "-" + GetParam().name);
    fs::create_directories(mDir);
    ASSERT_EQ(makeStore(mDir), "");
    auto s = Session::open(mDir / "grid.json", mCaps);
    ASSERT_TRUE(s.ok()) << s.diagnostics.format();
    auto rt = gl::RenderTarget::create(kW, kH);
    ASSERT_TRUE(rt.ok());
    const math::Aabb b = (*s)->terrain().bounds();
    const glm::dvec3 c = b.center();
    const double range = 0.9 * (b.max.x - b.min.x), t = (*s)->startTime() + 1800.0;
    int sky = 0;
    for (int k = 0; k < 8; ++k)
        for (double pitch : {-25.0, -50.0}) {
            const math::Viewpoint vp{glm::dvec3(c.x, c.y, 1000), 45.0 * k, pitch, range};
            const math::Camera cam = makeCamera(vp, b, kW, kH, (*s)->scenario().camera.fovY);
            rt->bind();
            const std::string label = std::string(GetParam().name) + "-heading-" +
                                      std::to_string(45 * k) + "-pitch-" +
                                      std::to_string(int(-pitch));
            ASSERT_TRUE(test::settleView(**s, cam, t)) << label << ": tiles still loading";
            (*s)->drawFrame(cam, t, kW, kH);
            const gl::Image img = rt->readColor();
            const test::CrackCount n = test::crackPixels(img);
            sky += n.sky;
            if (n.cracks) {
                const char* root = std::getenv("KIOSK_TEST_OUTPUT");
                const fs::path out = fs::path(root && *root ? root : "build/golden-out") /
                                     ("cracks-" + label + ".png");
                fs::create_directories(out.parent_path());
                test::writeImage(out.string(), img);
            }
            EXPECT_EQ(n.cracks, 0)
                << label << ": " << n.cracks << " crack pixels, first at (" << n.firstX << ", "
                << n.firstY << "); frame written to golden-out/";
        }
    // The method needs background to flood from; without it every count would be 0.
    EXPECT_GT(sky, 0) << "no clear-colour pixel in any view: the views do not reach the sky";
}

INSTANTIATE_TEST_SUITE_P(Grids, GridCensus, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<GridCase>& i) {
                             return std::string(i.param.name);
                         });

}  // namespace
}  // namespace kiosk::app
