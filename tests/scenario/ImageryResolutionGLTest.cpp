// Imagery keeps its own resolution (issue 16): an orthophoto 8 x finer than the DEM is stored
// with pyramid levels below the elevation grid's finest and drawn at its own texel size. The
// test writes a 32 m DEM and a 4 m image of one-pixel stripes, imports both, renders a
// top-down view and measures the stripes' width on screen: about 4 m in pixels. Resampled to the
// DEM's grid (the old behaviour) the stripes averaged to flat grey.
#include "runtime/app/Session.h"
#include "runtime/import/Importer.h"
#include "runtime/io/StoreReader.h"
#include "tests/support/EglTestContext.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;
constexpr int kW = 480, kH = 270;

// A GeoTIFF of `bands` bands, `pixel` metres, north-west corner (500000, 5000000).
void writeTiff(const fs::path& p, int n, double pixel, int bands, GDALDataType type,
               const std::vector<float>& v) {
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), n, n, bands, type, nullptr);
    ASSERT_NE(ds, nullptr);
    double gt[6] = {500000, pixel, 0, 5000000, 0, -pixel};
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, import::test::wktOf(32610).c_str());
    for (int b = 1; b <= bands; ++b)
        ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b), GF_Write, 0, 0, n, n,
                               const_cast<float*>(v.data()), n, n, GDT_Float32, 0, 0),
                  CE_None);
    GDALClose(ds);
}

class ImageryResolution : public test::EglTest {};

TEST_F(ImageryResolution, FinerImageryIsDrawnAtItsOwnTexelSize) {
    const fs::path dir = fs::temp_directory_path() / "geokiosk-imagery-resolution";
    fs::remove_all(dir);
    fs::create_directories(dir);
    GDALAllRegister();
    std::vector<float> dem(64 * 64);
    for (int r = 0; r < 64; ++r)
        for (int c = 0; c < 64; ++c) dem[std::size_t(r * 64 + c)] = 100.0f + 0.25f * float(c);
    writeTiff(dir / "dem.tif", 64, 32.0, 1, GDT_Float32, dem);
    std::vector<float> stripes(512 * 512);
    for (int r = 0; r < 512; ++r)
        for (int c = 0; c < 512; ++c) stripes[std::size_t(r * 512 + c)] = (c % 2) ? 255.0f : 0.0f;
    writeTiff(dir / "ortho.tif", 512, 4.0, 3, GDT_Byte, stripes);
    import::ImportOptions o;
    o.store = dir / "s.gpkg";
    o.quiet = true;
    ASSERT_FALSE(import::importElevation((dir / "dem.tif").string(), o).hasErrors());
    o.name = "ortho";
    const Diagnostics d = import::importImagery((dir / "ortho.tif").string(), o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    {
        auto r = io::StoreReader::open(o.store);
        ASSERT_TRUE(r.ok());
        // 32 m grid, 4 m imagery: three levels below the grid's finest.
        EXPECT_EQ((*r)->info().findLayer("elevation")->levels, 1);
        EXPECT_EQ((*r)->info().findLayer("ortho")->levels, 4);
    }
    const double range = 300.0;
    std::ofstream(dir / "s.json") << R"({ "version": 1, "stores": { "s": "s.gpkg" },
  "terrain": { "store": "s", "elevation": "elevation", "tauGeom": 2, "tauTex": 1 },
  "layers": [ { "id": "ortho", "kind": "thematic", "source": { "store": "s", "layer": "ortho" } } ],
  "viewpoints": { "top": { "target": [500700, 4999300, 120], "heading": 0, "pitch": -89.9,
                           "range": )"
                                  << range << R"( } } })";
    auto rt = gl::RenderTarget::create(kW, kH);
    ASSERT_TRUE(rt.ok());
    auto s = Session::open(dir / "s.json", mCaps);
    ASSERT_TRUE(s.ok()) << s.diagnostics.format();
    Session& session = **s;
    const double t = session.startTime();
    auto vp = session.viewpointAt(t, "top");
    ASSERT_TRUE(vp.ok());
    const double fovY = 45.0;
    const math::Camera cam = makeCamera(*vp, session.terrain().bounds(), kW, kH, fovY);
    for (int k = 0; k < 30000 && (k == 0 || !session.terrain().settled()); ++k) {
        session.prepare(cam, t);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    rt->bind();
    session.drawFrame(cam, t, kW, kH);
    const gl::Image img = rt->readColor();

    // Runs of dark / bright pixels along the middle row (the stripes run north-south).
    const int y = kH / 2;
    std::vector<int> runs;
    int lo = 255, hi = 0, run = 0;
    bool bright = img.pixel(0, y)[0] > 127;
    for (int x = 0; x < kW; ++x) {
        const int v = img.pixel(x, y)[0];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        const bool b = v > 127;
        if (b != bright) {
            runs.push_back(run);
            run = 0;
            bright = b;
        }
        ++run;
    }
    ASSERT_GT(hi - lo, 150) << "no stripes: the imagery was resampled to the DEM's grid";
    ASSERT_GT(runs.size(), 10u);
    // Whole runs only (the first and last are cut by the frame).
    double sum = 0;
    for (std::size_t i = 1; i + 1 < runs.size(); ++i) sum += runs[i];
    const double texelPx = sum / double(runs.size() - 2);
    // Pixels per metre on the ground straight below the camera.
    const double ppm = kH / (2.0 * range * std::tan(fovY * M_PI / 360.0));
    std::printf("imagery texel on screen %.2f px (4 m = %.2f px, a DEM post = %.2f px)\n", texelPx,
                4.0 * ppm, 32.0 * ppm);
    EXPECT_NEAR(texelPx, 4.0 * ppm, 0.25 * 4.0 * ppm);
    EXPECT_LT(texelPx, 32.0 * ppm / 4.0) << "not finer than the DEM grid";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace kiosk::app
