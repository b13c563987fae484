// import sequence: GeoTIFF frames with times, NetCDF CF time axes, Cell2Fire grids.
#include "runtime/app/ImportCommand.h"
#include "runtime/app/InfoCommand.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "runtime/import/Pyramid.h"
#include "runtime/import/Topographic.h"
#include "runtime/io/StoreReader.h"
#include "runtime/topo/NormalMap.h"
#include "tests/unit/import/CfSequenceFile.h"
#include "tests/unit/import/ImportFixtures.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <netcdf.h>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import;
using namespace kiosk::import::test;

TEST(ImportSequence, GeoTiffFramesWithTimesCsvAndAppend) {
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(makeDem(dir).string(), options(store)).hasErrors());
    const double gt[6] = {550000 + 30 * 100, 30, 0, 5200000 - 30 * 50, 0, -30};
    std::vector<std::string> files;
    for (int f = 0; f < 4; ++f) {
        std::vector<float> v(100 * 80);
        for (int i = 0; i < 100 * 80; ++i)
            v[std::size_t(i)] = i % 100 < 10 ? -1.f : float(f) * 0.5f + float(i % 100) * 0.01f;
        const fs::path p = dir / ("frame" + std::to_string(f) + ".tif");
        writeTiff(p, 100, 80, gt, 32610, v, -1.0);
        files.push_back(p.string());
    }
    {
        std::ofstream csv(dir / "times.csv");
        csv << "file,time\n";
        csv << "frame0.tif,2024-05-01T00:00:00Z\nframe1.tif,2024-05-01T00:30:00Z\nframe2.tif,2024-"
               "05-01T02:00:00Z\n";
    }
    ImportOptions o = options(store);
    o.name = "flood_depth";
    o.units = "m";
    o.timesCsv = (dir / "times.csv").string();
    Diagnostics d = importSequence({files[0], files[1], files[2]}, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    {
        auto r = openStore(store);
        const auto* s = r->info().findSequence("flood_depth");
        ASSERT_NE(s, nullptr);
        ASSERT_EQ(s->frameTimes.size(), 3u);
        EXPECT_EQ(formatIso8601(s->frameTimes[1]), "2024-05-01T00:30:00Z");
        EXPECT_EQ(s->units, "m");
        EXPECT_NEAR(s->frameMin[2], 1.1, 0.01);
        EXPECT_NEAR(s->frameMax[2], 1.99, 0.01);
        auto tile = r->readSequenceFrame("flood_depth", 2, TileId{2, 0, 0});
        ASSERT_TRUE(tile.ok()) << tile.diagnostics.format();
        EXPECT_NEAR(tile->at(100 + 37, 50 + 3), 1.0 + 0.37, 1e-3);
        EXPECT_TRUE(std::isnan(tile->at(100 + 5, 50 + 3)));
        EXPECT_TRUE(std::isnan(tile->at(50, 10)));
        EXPECT_TRUE(r->readSequenceFrame("flood_depth", 0, TileId{0, 0, 0}).ok());
    }
    // Append one frame later in time; an earlier one is refused and leaves the store as it was.
    ImportOptions a = options(store);
    a.name = "flood_depth";
    a.timesCsv.reset();
    const fs::path later = dir / "depth_20240501T0300.tif";
    fs::copy_file(files[3], later);
    ASSERT_FALSE(importSequence({later.string()}, a).hasErrors());
    const std::string before = fileBytes(store);
    const fs::path earlier = dir / "depth_20240430T2300.tif";
    fs::copy_file(files[3], earlier);
    Diagnostics bad = importSequence({earlier.string()}, a);
    ASSERT_TRUE(bad.hasErrors());
    EXPECT_EQ(bad.firstError()->code, "IMPORT_TIMES_UNSORTED");
    EXPECT_EQ(fileBytes(store), before);
    auto r = openStore(store);
    const auto* s = r->info().findSequence("flood_depth");
    ASSERT_EQ(s->frameTimes.size(), 4u);
    EXPECT_EQ(formatIso8601(s->frameTimes[3]), "2024-05-01T03:00:00Z");
    EXPECT_TRUE(leftovers(dir).empty());
}

TEST(ImportSequence, NetCdfWithCfTimeAxis) {
    const fs::path dir = testDir();
    const fs::path nc = dir / "depth.nc";
    CfSequenceFile f;
    f.nx = 30;
    f.ny = 20;
    f.cell = 10;
    f.top = 1000;
    f.times = {0, 12, 36};
    f.timeUnits = "hours since 2001-02-28 12:00:00";
    f.calendar = "noleap";
    f.fill = -999.f;
    f.value = [](int k, int i) { return float(k) + float(i % 30) * 0.1f; };
    f.write(nc);

    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    o.name = "depth";
    o.variable = "depth";
    Diagnostics d = importSequence({nc.string()}, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    const auto* s = r->info().findSequence("depth");
    ASSERT_NE(s, nullptr);
    ASSERT_EQ(s->frameTimes.size(), 3u);
    EXPECT_EQ(formatIso8601(s->frameTimes[0]), "2001-02-28T12:00:00Z");
    EXPECT_EQ(formatIso8601(s->frameTimes[1]), "2001-03-01T00:00:00Z");
    EXPECT_EQ(formatIso8601(s->frameTimes[2]), "2001-03-02T00:00:00Z");
    EXPECT_DOUBLE_EQ(r->info().grid.levels.back().pixelXSize, 10.0);
    auto tile = r->readSequenceFrame("depth", 2, TileId{0, 0, 0});
    ASSERT_TRUE(tile.ok()) << tile.diagnostics.format();
    EXPECT_NEAR(tile->at(7, 4), 2.7, 1e-3);
    EXPECT_NEAR(tile->at(29, 19), 2.0 + 2.9, 1e-3);
}

// CAMS regional forecasts state `time:units = "hours"` with no reference date in the units: the
// message names the option that gives it, and with --start the hours count from it.
TEST(ImportSequence, ForecastHoursWithoutSinceTakeTheReferenceFromStart) {
    const fs::path dir = testDir();
    const fs::path nc = dir / "forecast.nc";
    CfSequenceFile f;
    f.times = {0, 12, 36};
    f.timeUnits = "hours";
    f.write(nc);
    const fs::path store = dir / "forecast.gpkg";
    ImportOptions o = options(store);
    o.name = "depth";
    o.variable = "depth";
    Diagnostics d = importSequence({nc.string()}, o);
    ASSERT_TRUE(d.hasErrors());
    ASSERT_EQ(d.items().size(), 1u) << d.format();
    EXPECT_EQ(d.firstError()->code, "CF_TIME_UNITS");
    EXPECT_EQ(d.firstError()->file, nc.string());
    EXPECT_NE(d.firstError()->message.find("give the forecast's reference time with --start"),
              std::string::npos)
        << d.format();
    o.start = parseIso8601("2024-06-01T00:00:00Z");
    d = importSequence({nc.string()}, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    const auto* s = r->info().findSequence("depth");
    ASSERT_NE(s, nullptr);
    ASSERT_EQ(s->frameTimes.size(), 3u);
    EXPECT_EQ(formatIso8601(s->frameTimes[0]), "2024-06-01T00:00:00Z");
    EXPECT_EQ(formatIso8601(s->frameTimes[1]), "2024-06-01T12:00:00Z");
    EXPECT_EQ(formatIso8601(s->frameTimes[2]), "2024-06-02T12:00:00Z");
}

TEST(ImportSequence, Cell2FireBurnGridsKeepTheirCounts) {
    const std::string grids = sharedData("cell2fire_fire_spread/Harvest40x40/Grids/Grids1");
    if (grids.empty()) GTEST_SKIP() << "../shared/data not present (set KIOSK_SHARED_DATA)";
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    o.name = "fire";
    o.start = *parseIso8601("2001-10-16T13:00:00Z");
    Diagnostics d = importSequence({grids}, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    const auto* s = r->info().findSequence("fire");
    ASSERT_NE(s, nullptr);
    EXPECT_TRUE(s->categorical);
    ASSERT_EQ(s->frameTimes.size(), 16u);
    EXPECT_EQ(formatIso8601(s->frameTimes[15]), "2001-10-17T04:00:00Z");
    const int expected[16] = {1,   4,   25,  61,  85,  121, 154, 175,
                              182, 192, 202, 210, 217, 223, 55,  300};
    EXPECT_DOUBLE_EQ(r->info().grid.levels.back().pixelXSize, 100.0);
    EXPECT_DOUBLE_EQ(r->info().grid.minX, 457900.0);
    for (int f = 0; f < 16; ++f) {
        auto tile = r->readSequenceFrame("fire", f, TileId{0, 0, 0});
        ASSERT_TRUE(tile.ok());
        int burned = 0, breaks = 0;
        for (int yy = 0; yy < 40; ++yy)
            for (int xx = 0; xx < 40; ++xx) {
                burned += tile->at(xx, yy) == 1.f;
                breaks += tile->at(xx, yy) == -1.f;
            }
        EXPECT_EQ(burned, expected[f]) << "frame " << f;
        EXPECT_EQ(breaks, 40) << "frame " << f;
    }
    EXPECT_EQ(validateGpkg(store), "");
}
