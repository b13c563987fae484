// import elevation / imagery / topographic: values, grids and GDAL agreeing.
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

TEST(ImportElevation, SmallDemRoundTripsWithinDeclaredPrecision) {
    const fs::path dir = testDir();
    std::vector<float> src;
    const fs::path dem = makeDem(dir, &src);
    const fs::path store = dir / "s.gpkg";
    Diagnostics d = importElevation(dem.string(), options(store));
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    ASSERT_TRUE(r);
    const auto& info = r->info();
    EXPECT_EQ(info.grid.srsId, 32610);
    ASSERT_EQ(info.grid.levels.size(), 3u);  // 600 px -> 1024 = 256 * 2^2
    EXPECT_DOUBLE_EQ(info.grid.levels.back().pixelXSize, 30.0);
    EXPECT_DOUBLE_EQ(info.grid.levels[0].pixelXSize, 120.0);
    EXPECT_DOUBLE_EQ(info.grid.minX, 550000.0);
    const io::LayerInfo* l = info.findLayer("elevation");
    ASSERT_NE(l, nullptr);
    EXPECT_EQ(l->tileCount, 9 + 4 + 1);
    EXPECT_GT(l->precision, 0.0);
    EXPECT_LE(l->precision, 1.0 / 32.0);
    const auto got = finestArray(*r, "elevation", 600, 520);
    double worst = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        if (src[i] == -9999.f) {
            EXPECT_TRUE(std::isnan(got[i])) << i;
            continue;
        }
        worst = std::max(worst, double(std::fabs(got[i] - src[i])));
    }
    EXPECT_LE(worst, l->precision / 2 + 1e-4);
    float srcMin = 1e9f;
    for (float v : src)
        if (v != -9999.f) srcMin = std::min(srcMin, v);
    EXPECT_NEAR(l->minValue, srcMin, l->precision);
}

TEST(ImportElevation, FillVoidsInterpolatesTheNodataBlock) {
    const fs::path dir = testDir();
    std::vector<float> src;
    const fs::path dem = makeDem(dir, &src);
    ImportOptions o = options(dir / "filled.gpkg");
    o.fillVoids = true;
    Diagnostics d = importElevation(dem.string(), o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(o.store);
    ASSERT_TRUE(r);
    const auto got = finestArray(*r, "elevation", 600, 520);
    // The 40 x 30 void is filled with values inside the range of the valid cells around it.
    float lo = 1e9f, hi = -1e9f;
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 80; ++x) {
            const float v = src[std::size_t(y * 600 + x)];
            if (v != -9999.f) lo = std::min(lo, v), hi = std::max(hi, v);
        }
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            const float v = got[std::size_t(y * 600 + x)];
            ASSERT_FALSE(std::isnan(v)) << x << "," << y;
            EXPECT_GE(v, lo - 1.0f);
            EXPECT_LE(v, hi + 1.0f);
        }
    // Valid cells are untouched.
    EXPECT_NEAR(got[std::size_t(100 * 600 + 100)], src[std::size_t(100 * 600 + 100)], 0.05f);
}

TEST(ImportElevation, BorderPostsEqualNeighbourSamples) {
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(makeDem(dir).string(), options(store)).hasErrors());
    auto r = openStore(store);
    ASSERT_TRUE(r);
    const int t = 256;
    int checked = 0;
    for (int level = 0; level <= 2; ++level) {
        const int n = 1 << level;
        for (int row = 0; row < n; ++row)
            for (int col = 0; col < n; ++col) {
                auto a = r->readElevation("elevation", TileId{level, col, row});
                if (!a) continue;
                auto e = r->readElevation("elevation", TileId{level, col + 1, row});
                auto s = r->readElevation("elevation", TileId{level, col, row + 1});
                auto se = r->readElevation("elevation", TileId{level, col + 1, row + 1});
                for (int y = 0; y < t && e; ++y) {
                    if (std::isnan(e->at(0, y))) continue;
                    ASSERT_EQ(a->at(t, y), e->at(0, y)) << level << "/" << col << "/" << row;
                    ++checked;
                }
                for (int x = 0; x < t && s; ++x) {
                    if (std::isnan(s->at(x, 0))) continue;
                    ASSERT_EQ(a->at(x, t), s->at(x, 0));
                    ++checked;
                }
                if (se && !std::isnan(se->at(0, 0))) {
                    EXPECT_EQ(a->at(t, t), se->at(0, 0));
                }
            }
    }
    EXPECT_GT(checked, 2000);
    // At the data's east edge the border post replicates the last column.
    auto edge = r->readElevation("elevation", TileId{2, 2, 0});
    ASSERT_TRUE(edge.ok());
    EXPECT_TRUE(std::isnan(edge->at(t, 5)));  // data ends inside this tile (600 = 2*256 + 88)
    EXPECT_FALSE(std::isnan(edge->at(87, 5)));
    EXPECT_TRUE(std::isnan(edge->at(88, 5)));
}

TEST(ImportElevation, GeometricErrorIsAnUpperBoundOfBruteForce) {
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(makeDem(dir).string(), options(store)).hasErrors());
    auto r = openStore(store);
    ASSERT_TRUE(r);
    const int w = 600, h = 520, t = 256, L = 2;
    const auto full = finestArray(*r, "elevation", w, h);
    int tiles = 0;
    for (int level = 0; level < L; ++level) {
        const int k = 1 << (L - level);
        for (int row = 0; row < (1 << level); ++row)
            for (int col = 0; col < (1 << level); ++col) {
                auto tile = r->readElevation("elevation", TileId{level, col, row});
                if (!tile) {
                    continue;
                }
                ++tiles;
                double brute = 0;
                for (int y = 0; y < h; ++y) {
                    const double py = (y + 0.5) / k - 0.5 - row * t;
                    if (py < 0 || py > t) continue;
                    for (int x = 0; x < w; ++x) {
                        const double px = (x + 0.5) / k - 0.5 - col * t;
                        if (px < 0 || px > t) continue;
                        const float f = full[std::size_t(y * w + x)];
                        if (std::isnan(f)) continue;
                        const int x0 = std::min(int(px), t - 1), y0 = std::min(int(py), t - 1);
                        const double fx = px - x0, fy = py - y0;
                        const double s = (1 - fx) * (1 - fy) * tile->at(x0, y0) +
                                         fx * (1 - fy) * tile->at(x0 + 1, y0) +
                                         (1 - fx) * fy * tile->at(x0, y0 + 1) +
                                         fx * fy * tile->at(x0 + 1, y0 + 1);
                        if (std::isnan(s)) continue;
                        brute = std::max(brute, std::fabs(s - f));
                    }
                }
                SCOPED_TRACE(::testing::Message() << level << "/" << col << "/" << row);
                EXPECT_GT(brute, 0.1);  // the test surface is rough: coarse levels do deviate
                EXPECT_LE(brute, tile->stats.geometricError + 1e-3);
                EXPECT_LE(tile->stats.geometricError, 4 * brute + 1.0);  // and not absurdly loose
            }
    }
    EXPECT_EQ(tiles, 5);
    auto finest = r->tileStats("elevation", TileId{2, 0, 0});
    ASSERT_TRUE(finest.has_value());
    EXPECT_EQ(finest->geometricError, 0.f);
}

TEST(ImportElevation, GdalReadsTheStoreAndAgrees) {
    if (!haveTool("gdallocationinfo")) GTEST_SKIP() << "gdal-bin not installed";
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(makeDem(dir).string(), options(store)).hasErrors());
    GDALAllRegister();
    GDALDatasetH ds = GDALOpen(store.c_str(), GA_ReadOnly);
    ASSERT_NE(ds, nullptr);
    EXPECT_STREQ(GDALGetDriverShortName(GDALGetDatasetDriver(ds)), "GPKG");
    EXPECT_EQ(GDALGetRasterXSize(ds), 600);
    EXPECT_EQ(GDALGetRasterYSize(ds), 520);
    EXPECT_EQ(GDALGetOverviewCount(GDALGetRasterBand(ds, 1)), 2);
    GDALClose(ds);
    auto r = openStore(store);
    const auto ours = finestArray(*r, "elevation", 600, 520);
    std::vector<std::pair<int, int>> px;
    std::mt19937 rng(3);
    for (int i = 0; i < 40; ++i) px.emplace_back(40 + int(rng() % 560), int(rng() % 520));
    const auto theirs = gdalLocationValues(store, px);
    ASSERT_EQ(theirs.size(), px.size());
    for (std::size_t i = 0; i < px.size(); ++i)
        EXPECT_NEAR(theirs[i], ours[std::size_t(px[i].second * 600 + px[i].first)], 1e-3)
            << px[i].first << "," << px[i].second;
}

TEST(ImportElevation, RealDemsFromSharedData) {
    const std::string dogrib = sharedData("cell2fire_fire_spread/dogrib/elevation.asc");
    const std::string rainier = sharedData("srtm90_osgearth/mt_rainier_90m.tif");
    const std::string puget = sharedData("puget_sound_heightmap/ps_height_1k.png");
    if (dogrib.empty() || rainier.empty() || puget.empty())
        GTEST_SKIP() << "../shared/data not present (set KIOSK_SHARED_DATA)";
    const fs::path dir = testDir();
    GDALAllRegister();
    auto readAll = [](const std::string& path, int& w, int& h) {
        GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
        w = GDALGetRasterXSize(ds);
        h = GDALGetRasterYSize(ds);
        std::vector<float> v(std::size_t(w) * std::size_t(h));
        EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, w, h, v.data(), w, h,
                               GDT_Float32, 0, 0),
                  CE_None);
        GDALClose(ds);
        return v;
    };
    {  // Integer metres, no CRS (local CRS): exact.
        const fs::path store = dir / "dogrib.gpkg";
        Diagnostics d = importElevation(dogrib, options(store));
        ASSERT_FALSE(d.hasErrors()) << d.format();
        EXPECT_TRUE(d.has("IMPORT_LOCAL_CRS"));
        int w, h;
        const auto src = readAll(dogrib, w, h);
        auto r = openStore(store);
        const auto got = finestArray(*r, "elevation", w, h);
        for (std::size_t i = 0; i < src.size(); ++i) ASSERT_EQ(got[i], src[i]) << i;
        EXPECT_EQ(r->info().findLayer("elevation")->minValue, 1299);
        EXPECT_EQ(r->info().findLayer("elevation")->maxValue, 2825);
    }
    {  // PNG heightmap without georeferencing: --pixel-size and --z-scale.
        const fs::path store = dir / "puget.gpkg";
        ImportOptions o = options(store);
        EXPECT_TRUE(importElevation(puget, o).has("IMPORT_NO_GEOREF"));
        o.pixelSize = 160;
        o.zScale = 0.1;
        Diagnostics d = importElevation(puget, o);
        ASSERT_FALSE(d.hasErrors()) << d.format();
        int w, h;
        const auto src = readAll(puget, w, h);
        auto r = openStore(store);
        EXPECT_DOUBLE_EQ(r->info().grid.levels.back().pixelXSize, 160.0);
        const double prec = r->info().findLayer("elevation")->precision;
        const auto got = finestArray(*r, "elevation", w, h);
        double worst = 0;
        for (std::size_t i = 0; i < src.size(); ++i)
            worst = std::max(worst, std::fabs(double(got[i]) - double(src[i]) * 0.1));
        EXPECT_LE(worst, prec / 2 + 1e-4);
    }
    {  // Geographic SRTM with voids: warped to UTM 10N, GDAL agrees with our reader.
        const fs::path store = dir / "rainier.gpkg";
        Diagnostics d = importElevation(rainier, options(store));
        ASSERT_FALSE(d.hasErrors()) << d.format();
        auto r = openStore(store);
        EXPECT_EQ(r->info().grid.srsId, 32610);
        const auto* l = r->info().findLayer("elevation");
        EXPECT_GT(l->minValue, 250);
        EXPECT_LT(l->maxValue, 4372);
        EXPECT_GT(l->maxValue, 4300);
        if (haveTool("gdallocationinfo")) {
            // Summit of Mount Rainier (46.853 N, 121.760 W): 4392 m; SRTM 90 m says ~4370.
            const std::string cmd =
                "gdallocationinfo -valonly -wgs84 '" + store.string() + "' -121.7603 46.8528";
            FILE* p = popen(cmd.c_str(), "r");
            char line[64] = {0};
            ASSERT_TRUE(std::fgets(line, sizeof line, p));
            pclose(p);
            EXPECT_NEAR(std::strtod(line, nullptr), 4360, 40);
        }
    }
}

TEST(ImportImagery, ImageryLandsOnTheStoreGrid) {
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(makeDem(dir).string(), options(store)).hasErrors());
    // RGB image over the east half of the DEM, same 30 m grid.
    const int w = 300, h = 520;
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), (dir / "img.tif").c_str(), w, h, 3,
                                 GDT_Byte, nullptr);
    const double gt[6] = {550000 + 300 * 30, 30, 0, 5200000, 0, -30};
    GDALSetGeoTransform(ds, const_cast<double*>(gt));
    GDALSetProjection(ds, wktOf(32610).c_str());
    std::vector<std::uint8_t> band(std::size_t(w * h));
    for (int b = 1; b <= 3; ++b) {
        for (int i = 0; i < w * h; ++i)
            band[std::size_t(i)] = std::uint8_t(b == 1 ? i % w : b == 2 ? (i / w) % 256 : 77);
        ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b), GF_Write, 0, 0, w, h, band.data(), w, h,
                               GDT_Byte, 0, 0),
                  CE_None);
    }
    GDALClose(ds);
    ImportOptions o = options(store);
    o.name = "photo";
    Diagnostics d = importImagery((dir / "img.tif").string(), o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    const auto* l = r->info().findLayer("photo");
    ASSERT_NE(l, nullptr);
    EXPECT_EQ(l->kind, io::LayerKind::Imagery);
    // Finest tile (1, 0) holds image columns 0..211 at grid columns 300..511.
    auto tile = r->readImagery("photo", TileId{2, 1, 0});
    ASSERT_TRUE(tile.ok()) << tile.diagnostics.format();
    const int gx = 300 + 17, gy = 9;
    const std::uint8_t* p = &tile->rgba[std::size_t(gy * 256 + (gx - 256)) * 4];
    EXPECT_NEAR(p[0], 17, 1);
    EXPECT_NEAR(p[1], 9, 1);
    EXPECT_NEAR(p[2], 77, 1);
    EXPECT_EQ(p[3], 255);
    const std::uint8_t* west = &tile->rgba[std::size_t(gy * 256 + 10) * 4];  // grid col 266
    EXPECT_EQ(west[3], 0);
    EXPECT_TRUE(r->readImagery("photo", TileId{0, 0, 0}).ok());
    EXPECT_EQ(validateGpkg(store), "");
}

TEST(ImportElevation, FeetDemIsConvertedAndMismatchIsRefused) {
    const std::string before = sharedData("mt_st_helens_usgs_dem/mtsthelens_before.zip");
    const std::string after = sharedData("mt_st_helens_usgs_dem/mtsthelens_after.zip");
    if (before.empty() || after.empty())
        GTEST_SKIP() << "../shared/data not present (set KIOSK_SHARED_DATA)";
    const fs::path dir = testDir();
    const fs::path store = dir / "helens.gpkg";
    const std::string b = "/vsizip/" + before + "/30.1.1.1282760.dem";
    const std::string a = "/vsizip/" + after + "/10.2.1.1043901.dem";
    Diagnostics d = importElevation(b, options(store));
    ASSERT_FALSE(d.hasErrors()) << d.format();
    ImportOptions o = options(store);
    o.name = "after";
    o.units = "m";
    Diagnostics bad = importElevation(a, o);
    ASSERT_TRUE(bad.hasErrors());
    EXPECT_EQ(bad.firstError()->code, "IMPORT_UNITS_MISMATCH");
    EXPECT_NE(bad.format().find("declares its values in 'ft' but --units m"), std::string::npos);
    o.units.reset();
    d = importElevation(a, o);  // 10 m NAD27 feet onto the 30 m grid of the first import
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    const auto* pre = r->info().findLayer("elevation");
    const auto* post = r->info().findLayer("after");
    ASSERT_NE(post, nullptr);
    EXPECT_NEAR(pre->maxValue, 2951, 1.0);
    EXPECT_GT(post->maxValue, 2400);               // 8367 ft = 2550 m, resampled to 30 m
    EXPECT_LT(post->maxValue, 8367 * 0.3048 + 1);  // metres, not feet
    EXPECT_EQ(post->levels, pre->levels);
}

// `import topographic --normals`: the finest level holds exactly topo::normalMap of the store's
// own full-resolution elevation (Rgb8 in RGB, validity in A); nodata and the area beyond the
// DEM are transparent zero texels (no rim); coarser levels exist.
TEST(ImportTopographic, NormalMapEqualsNormalMapOfTheStoredElevation) {
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(makeDem(dir).string(), options(store)).hasErrors());
    TopographicOptions o;
    o.store = store;
    o.normals = true;
    o.name = "normals";
    o.quiet = true;
    const Diagnostics d = importTopographic(o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    const auto* l = r->info().findLayer("normals");
    ASSERT_NE(l, nullptr);
    EXPECT_EQ(l->kind, io::LayerKind::Imagery);
    const auto& g = r->info().grid;
    const int t = g.levels.back().tileWidth, L = g.maxLevel();
    const int W = g.levels.back().matrixWidth * t, H = g.levels.back().matrixHeight * t;
    const std::vector<float> dem = finestArray(*r, "elevation", W, H);
    topo::RasterView v = topo::RasterView::window(
        dem.data(), W, H, W, 0, 0, W, H, g.levels.back().pixelXSize, g.levels.back().pixelYSize);
    std::vector<std::uint8_t> want(std::size_t(W) * std::size_t(H) * 3);
    ASSERT_FALSE(topo::normalMap(v, {}, want.data(), W * 3).hasErrors());
    int compared = 0, nodata = 0, mismatched = 0;
    for (int row = 0; row * t < H; ++row)
        for (int col = 0; col * t < W; ++col) {
            auto tile = r->readImagery("normals", TileId{L, col, row});
            if (!tile) continue;
            for (int y = 0; y < t; ++y)
                for (int x = 0; x < t; ++x) {
                    const std::uint8_t* p = &tile->rgba[std::size_t(y * t + x) * 4];
                    const std::uint8_t* q = &want[(std::size_t(row * t + y) * std::size_t(W) +
                                                   std::size_t(col * t + x)) *
                                                  3];
                    const bool valid = q[2] != 0;
                    if (!valid) {
                        ++nodata;
                        mismatched += (p[0] | p[1] | p[2] | p[3]) != 0;
                        continue;
                    }
                    ++compared;
                    mismatched += p[0] != q[0] || p[1] != q[1] || p[2] != q[2] || p[3] != 255;
                }
        }
    EXPECT_GT(compared, 590 * 510);
    EXPECT_GT(nodata, 38 * 28);  // the nodata block, and beyond the DEM where tiles exist
    EXPECT_EQ(mismatched, 0);
    // The nodata block (DEM x < 40, y < 30) is transparent, its neighbours are shaded.
    auto first = r->readImagery("normals", TileId{L, 0, 0});
    ASSERT_TRUE(first.ok()) << first.diagnostics.format();
    EXPECT_EQ(first->rgba[std::size_t(10 * t + 10) * 4 + 3], 0);
    EXPECT_EQ(first->rgba[std::size_t(100 * t + 100) * 4 + 3], 255);
    EXPECT_GE(first->rgba[std::size_t(100 * t + 100) * 4 + 2], 128);  // normal points up
    EXPECT_TRUE(r->readImagery("normals", TileId{0, 0, 0}).ok());
    EXPECT_EQ(validateGpkg(store), "");
}
