// A store as GDAL and QGIS users see it (docs/store-format.md "Checking a store with GDAL"):
// each coverage's Min/Max is its own even with several coverages in the store, a hillshade's
// extent is its elevation's data extent (not the whole tile matrix), the sequences' time steps
// are an attributes table OGR lists, and GDAL's validate_gpkg.py still passes.
#include "runtime/import/Topographic.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_api.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import;
using namespace kiosk::import::test;

namespace {

// A UTM 10N Float32 GeoTIFF, 10 m pixels, north-west corner (x0, y0), values f(col, row).
void writeTiff(const fs::path& p, int w, int h, double x0, double y0, float (*f)(int, int)) {
    GDALAllRegister();
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), w, h, 1, GDT_Float32, nullptr);
    ASSERT_NE(ds, nullptr);
    double gt[6] = {x0, 10, 0, y0, 0, -10};
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, wktOf(32610).c_str());
    std::vector<float> v(std::size_t(w) * std::size_t(h));
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) v[std::size_t(r * w + c)] = f(c, r);
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, w, h, v.data(), w, h,
                           GDT_Float32, 0, 0),
              CE_None);
    GDALClose(ds);
}

GDALDatasetH openTable(const fs::path& store, const std::string& table) {
    const std::string opt = "TABLE=" + table;
    const char* const opts[] = {opt.c_str(), nullptr};
    return GDALOpenEx(store.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, opts, nullptr);
}

double statistic(GDALDatasetH ds, const char* item) {
    const char* v = GDALGetMetadataItem(GDALGetRasterBand(ds, 1), item, nullptr);
    return v ? std::strtod(v, nullptr) : -1e300;
}

}  // namespace

TEST(StoreForGdal, CoverageStatisticsExtentsAndSequenceTimes) {
    const fs::path dir = freshTestDir("geokiosk-store-gdal-test");
    const fs::path dem = dir / "dem.tif", f0 = dir / "depth_20240101T0000.tif",
                   f1 = dir / "depth_20240101T0100.tif";
    writeTiff(dem, 64, 48, 500000, 5000000, [](int c, int r) { return 100.0f + float(c + r); });
    // The flood covers a part of the terrain only, in other values than the elevation.
    writeTiff(f0, 24, 16, 500100, 4999900, [](int c, int) { return 0.25f * float(c % 5); });
    writeTiff(f1, 24, 16, 500100, 4999900, [](int c, int) { return 5.0f + float(c % 5); });
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(dem.string(), options(store)).hasErrors());
    ImportOptions so = options(store);
    so.name = "depth";
    const Diagnostics sd = importSequence({f0.string(), f1.string()}, so);
    ASSERT_FALSE(sd.hasErrors()) << sd.format();
    TopographicOptions to;
    to.store = store;
    to.quiet = true;
    const Diagnostics td = importTopographic(to);
    ASSERT_FALSE(td.hasErrors()) << td.format();

    auto r = openStore(store);
    ASSERT_TRUE(r);
    const auto* elev = r->info().findLayer("elevation");
    const auto* seq = r->info().findSequence("depth");
    ASSERT_TRUE(elev && seq);

    // Each coverage's Min/Max as GDAL reports them: its own (tile ids are store-unique).
    GDALDatasetH e = openTable(store, "elevation");
    ASSERT_NE(e, nullptr);
    EXPECT_DOUBLE_EQ(statistic(e, "STATISTICS_MINIMUM"), elev->minValue);
    EXPECT_DOUBLE_EQ(statistic(e, "STATISTICS_MAXIMUM"), elev->maxValue);
    for (int i = 0; i < 2; ++i) {
        GDALDatasetH f = openTable(store, "depth_f000" + std::to_string(i));
        ASSERT_NE(f, nullptr);
        EXPECT_DOUBLE_EQ(statistic(f, "STATISTICS_MINIMUM"), seq->frameMin[std::size_t(i)]);
        EXPECT_DOUBLE_EQ(statistic(f, "STATISTICS_MAXIMUM"), seq->frameMax[std::size_t(i)]);
        GDALClose(f);
    }

    // The hillshade is where the elevation is: the same raster size and origin in GDAL.
    GDALDatasetH h = openTable(store, "hillshade");
    ASSERT_NE(h, nullptr);
    double ge[6], gh[6];
    GDALGetGeoTransform(e, ge);
    GDALGetGeoTransform(h, gh);
    EXPECT_EQ(GDALGetRasterXSize(h), GDALGetRasterXSize(e));
    EXPECT_EQ(GDALGetRasterYSize(h), GDALGetRasterYSize(e));
    EXPECT_EQ(GDALGetRasterXSize(e), 64);
    EXPECT_EQ(GDALGetRasterYSize(e), 48);
    for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(gh[k], ge[k]) << k;
    GDALClose(h);
    GDALClose(e);

    // The time steps, as OGR (and so QGIS) lists them: one row per frame.
    GDALDatasetH v =
        GDALOpenEx(store.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    ASSERT_NE(v, nullptr) << "OGR finds no table in the store";
    OGRLayerH times = GDALDatasetGetLayerByName(v, "kiosk_sequence_times");
    ASSERT_NE(times, nullptr);
    EXPECT_EQ(OGR_L_GetFeatureCount(times, TRUE), 2);
    OGR_L_ResetReading(times);
    std::vector<std::string> got;
    while (OGRFeatureH feat = OGR_L_GetNextFeature(times)) {
        got.push_back(
            std::string(OGR_F_GetFieldAsString(feat, OGR_F_GetFieldIndex(feat, "time_utc"))) + " " +
            OGR_F_GetFieldAsString(feat, OGR_F_GetFieldIndex(feat, "table_name")));
        OGR_F_Destroy(feat);
    }
    EXPECT_EQ(got, (std::vector<std::string>{"2024-01-01T00:00:00Z depth_f0000",
                                             "2024-01-01T01:00:00Z depth_f0001"}));
    GDALClose(v);

    // GDAL's own validator (python3-gdal), when installed.
    const char* script = "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py";
    if (fs::exists(script) && fs::exists("/usr/bin/python3")) {
        const std::string cmd =
            "/usr/bin/python3 " + std::string(script) + " '" + store.string() + "'";
        EXPECT_EQ(std::system(cmd.c_str()), 0);
    }
}
