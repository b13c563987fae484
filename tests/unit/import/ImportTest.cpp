#include "runtime/app/ImportCommand.h"
#include "runtime/app/InfoCommand.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "runtime/import/Pyramid.h"
#include "runtime/import/Topographic.h"
#include "runtime/io/StoreReader.h"
#include "runtime/topo/NormalMap.h"
#include "tests/unit/import/CfSequenceFile.h"
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

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

fs::path testDir() {
    return import::test::freshTestDir("geokiosk-import-test");
}

std::string sharedData(const std::string& rel) {
    const char* root = std::getenv("KIOSK_SHARED_DATA");
    fs::path base = root ? fs::path(root) : fs::path("../shared/data");
    fs::path p = base / rel;
    return fs::exists(p) ? p.string() : std::string();
}

void writeTiff(const fs::path& p, int w, int h, const double gt[6], int epsg,
               const std::vector<float>& v, std::optional<double> nodata = std::nullopt,
               const char* unit = nullptr) {
    GDALAllRegister();
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), w, h, 1, GDT_Float32, nullptr);
    ASSERT_NE(ds, nullptr);
    GDALSetGeoTransform(ds, const_cast<double*>(gt));
    if (epsg) GDALSetProjection(ds, wktOf(epsg).c_str());
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    if (nodata) GDALSetRasterNoDataValue(b, *nodata);
    if (unit) GDALSetRasterUnitType(b, unit);
    ASSERT_EQ(GDALRasterIO(b, GF_Write, 0, 0, w, h, const_cast<float*>(v.data()), w, h, GDT_Float32,
                           0, 0),
              CE_None);
    GDALClose(ds);
}

float demValue(int x, int y) {
    return 1000.0f + 300.0f * std::sin(float(x) / 50.0f) * std::cos(float(y) / 70.0f) +
           0.5f * float((x * y) % 13);
}

// A 600 x 520 DEM in UTM 10N, 30 m pixels, with a nodata block.
fs::path makeDem(const fs::path& dir, std::vector<float>* values = nullptr) {
    const int w = 600, h = 520;
    std::vector<float> v(std::size_t(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            v[std::size_t(y * w + x)] = (x < 40 && y < 30) ? -9999.f : demValue(x, y);
    const double gt[6] = {550000, 30, 0, 5200000, 0, -30};
    const fs::path p = dir / "dem.tif";
    writeTiff(p, w, h, gt, 32610, v, -9999.0);
    if (values) *values = v;
    return p;
}

// The finest level of a scalar layer assembled into one array (window of the grid from 0,0).
std::vector<float> finestArray(io::StoreReader& r, const std::string& layer, int w, int h,
                               int frame = -1) {
    const auto& g = r.info().grid;
    const int t = g.levels.back().tileWidth, L = g.maxLevel();
    std::vector<float> out(std::size_t(w) * std::size_t(h), kNaN);
    for (int row = 0; row * t < h; ++row)
        for (int col = 0; col * t < w; ++col) {
            auto tile = frame < 0 ? r.readElevation(layer, TileId{L, col, row})
                                  : r.readSequenceFrame(layer, frame, TileId{L, col, row});
            if (!tile) continue;
            for (int y = 0; y < t && row * t + y < h; ++y)
                for (int x = 0; x < t && col * t + x < w; ++x)
                    out[std::size_t(row * t + y) * std::size_t(w) + std::size_t(col * t + x)] =
                        tile->at(x, y);
        }
    return out;
}

std::vector<double> gdalLocationValues(const fs::path& store,
                                       const std::vector<std::pair<int, int>>& px) {
    const fs::path in = store.string() + ".coords";
    {
        std::ofstream f(in);
        for (auto [x, y] : px) f << x << " " << y << "\n";
    }
    const std::string cmd =
        "gdallocationinfo -valonly '" + store.string() + "' < '" + in.string() + "'";
    std::vector<double> out;
    if (FILE* p = popen(cmd.c_str(), "r")) {
        char line[256];
        while (std::fgets(line, sizeof line, p)) out.push_back(std::strtod(line, nullptr));
        pclose(p);
    }
    return out;
}

// GDAL's own GeoPackage validator (python3-gdal), when installed: "" if valid or absent.
std::string validateGpkg(const fs::path& store) {
    const char* script = "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py";
    if (!fs::exists(script) || !haveTool("python3")) return "";
    const std::string cmd = std::string("python3 ") + script + " '" + store.string() + "' 2>&1";
    std::string out;
    if (FILE* p = popen(cmd.c_str(), "r")) {
        char line[512];
        while (std::fgets(line, sizeof line, p)) out += line;
        if (pclose(p) == 0) return "";
    }
    return out.empty() ? "validator failed" : out;
}

std::vector<std::string> leftovers(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find(".tmp-") != std::string::npos)
            out.push_back(e.path().string());
    return out;
}

/** @brief A SWW mesh as the tests read it independently of the importer (netCDF directly). */
struct SwwTestMesh {
    std::vector<double> x, y;  ///< relative to (xll, yll)
    std::vector<int> tri;
    double xll = 0, yll = 0;

    /**
     * @brief Linear interpolation of per-vertex values `value(i)` at (cx, cy) (mesh-relative),
     * from the first triangle containing the point; NaN outside the mesh.
     */
    template <class Value>
    double valueAt(double cx, double cy, Value value) const {
        for (std::size_t t = 0; t < tri.size() / 3; ++t) {
            const int a = tri[t * 3], b = tri[t * 3 + 1], c = tri[t * 3 + 2];
            const double det = (y[b] - y[c]) * (x[a] - x[c]) + (x[c] - x[b]) * (y[a] - y[c]);
            const double l1 = ((y[b] - y[c]) * (cx - x[c]) + (x[c] - x[b]) * (cy - y[c])) / det;
            const double l2 = ((y[c] - y[a]) * (cx - x[c]) + (x[a] - x[c]) * (cy - y[c])) / det;
            const double l3 = 1 - l1 - l2;
            if (l1 < -1e-9 || l2 < -1e-9 || l3 < -1e-9) continue;
            return l1 * value(a) + l2 * value(b) + l3 * value(c);
        }
        return std::nan("");
    }
};

SwwTestMesh readSwwTestMesh(int ncid, std::size_t points, std::size_t volumes) {
    SwwTestMesh m;
    m.x.resize(points);
    m.y.resize(points);
    m.tri.resize(volumes * 3);
    int v;
    nc_inq_varid(ncid, "x", &v);
    nc_get_var_double(ncid, v, m.x.data());
    nc_inq_varid(ncid, "y", &v);
    nc_get_var_double(ncid, v, m.y.data());
    nc_inq_varid(ncid, "volumes", &v);
    nc_get_var_int(ncid, v, m.tri.data());
    nc_get_att_double(ncid, NC_GLOBAL, "xllcorner", &m.xll);
    nc_get_att_double(ncid, NC_GLOBAL, "yllcorner", &m.yll);
    return m;
}

std::string fileBytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

}  // namespace

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

TEST(ImportSequence, AnugaSwwDepthMatchesStageMinusElevation) {
    const std::string sww = sharedData("anuga_sww_flood_timeseries/Small_catchment_testcase.sww");
    if (sww.empty()) GTEST_SKIP() << "../shared/data not present (set KIOSK_SHARED_DATA)";
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    o.name = "flood";
    o.pixelSize = 10;
    o.wetThreshold = 0.001;
    Diagnostics d = importSequence({sww}, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    const auto* s = r->info().findSequence("flood");
    ASSERT_NE(s, nullptr);

    // Independent read of the mesh.
    int id;
    ASSERT_EQ(nc_open(sww.c_str(), NC_NOWRITE, &id), NC_NOERR);
    int v;
    std::size_t np, nv, nt;
    int dim;
    nc_inq_dimid(id, "number_of_points", &dim);
    nc_inq_dimlen(id, dim, &np);
    nc_inq_dimid(id, "number_of_volumes", &dim);
    nc_inq_dimlen(id, dim, &nv);
    nc_inq_dimid(id, "number_of_timesteps", &dim);
    nc_inq_dimlen(id, dim, &nt);
    const SwwTestMesh mesh = readSwwTestMesh(id, np, nv);
    const auto &x = mesh.x, &y = mesh.y;
    const auto& tri = mesh.tri;
    const double xll = mesh.xll, yll = mesh.yll;
    std::vector<double> time(nt);
    nc_inq_varid(id, "time", &v);
    nc_get_var_double(id, v, time.data());
    ASSERT_EQ(s->frameTimes.size(), nt);
    for (std::size_t i = 0; i < nt; ++i) EXPECT_DOUBLE_EQ(s->frameTimes[i], time[i]);
    const int step = int(nt) - 1;
    std::vector<float> stage(np), elev(np);
    const std::size_t start[2] = {std::size_t(step), 0}, count[2] = {1, np};
    nc_inq_varid(id, "stage", &v);
    nc_get_vara_float(id, v, start, count, stage.data());
    nc_inq_varid(id, "elevation", &v);
    nc_get_vara_float(id, v, start, count, elev.data());
    nc_close(id);

    const auto& g = r->info().grid;
    const double p = g.levels.back().pixelXSize;
    const int L = g.maxLevel();
    std::mt19937 rng(11);
    int checked = 0, wet = 0;
    for (int n = 0; n < 400 && checked < 150; ++n) {
        // A vertex's pixel; the pixel centre lies in one of the vertex's triangles.
        const std::size_t t0 = rng() % nv;
        const std::size_t vi = std::size_t(tri[t0 * 3]);
        const int gx = int((x[vi] + xll - g.minX) / p), gy = int((g.maxY - (y[vi] + yll)) / p);
        const double cx = g.minX + (gx + 0.5) * p - xll, cy = g.maxY - (gy + 0.5) * p - yll;
        double expected = mesh.valueAt(
            cx, cy, [&](int i) { return double(stage[std::size_t(i)] - elev[std::size_t(i)]); });
        if (expected < 0.001) expected = 0;  // dry below the import's wet threshold (NaN stays)
        if (std::isnan(expected)) continue;
        auto tile = r->readSequenceFrame("flood", step, TileId{L, gx / 256, gy / 256});
        ASSERT_TRUE(tile.ok()) << tile.diagnostics.format();
        EXPECT_NEAR(tile->at(gx % 256, gy % 256), expected, 1e-3) << gx << "," << gy;
        ++checked;
        wet += expected > 0;
    }
    EXPECT_GT(checked, 100);
    EXPECT_GT(wet, 0);
}

// `import elevation X.sww`: the bed rasterised on the grid its depth sequence uses, so a
// SWW-only store has a terrain (issue 6, ANUGA replay).
TEST(ImportElevation, AnugaSwwBedSharesTheDepthGrid) {
    const std::string sww = sharedData("anuga_sww_flood_timeseries/Small_catchment_testcase.sww");
    if (sww.empty()) GTEST_SKIP() << "../shared/data not present (set KIOSK_SHARED_DATA)";
    const fs::path dir = testDir();
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    Diagnostics d = importElevation(sww, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    ImportOptions so = options(store);
    so.name = "flood";
    d = importSequence({sww}, so);
    ASSERT_FALSE(d.hasErrors()) << d.format();

    // The grid an elevation-first store gets is the one a sequence-only import defines.
    const fs::path alone = dir / "alone.gpkg";
    ImportOptions ao = options(alone);
    ao.name = "flood";
    ASSERT_FALSE(importSequence({sww}, ao).hasErrors());
    auto r = openStore(store);
    auto ra = openStore(alone);
    const auto& g = r->info().grid;
    const auto& ga = ra->info().grid;
    EXPECT_DOUBLE_EQ(g.minX, ga.minX);
    EXPECT_DOUBLE_EQ(g.maxY, ga.maxY);
    ASSERT_EQ(g.levels.size(), ga.levels.size());
    EXPECT_DOUBLE_EQ(g.levels.back().pixelXSize, ga.levels.back().pixelXSize);
    const auto* elev = r->info().findLayer("elevation");
    ASSERT_NE(elev, nullptr);
    EXPECT_EQ(elev->kind, io::LayerKind::Elevation);
    EXPECT_EQ(elev->levels, int(g.levels.size()));
    ASSERT_NE(r->info().findSequence("flood"), nullptr);

    // Independent read of the bed: at a pixel centre the linear interpolation of the vertex
    // elevations of the triangle holding it (ANUGA meshes have per-triangle vertices, so the
    // bed is discontinuous: compare with the containing triangle, not the nearest vertex).
    int id;
    ASSERT_EQ(nc_open(sww.c_str(), NC_NOWRITE, &id), NC_NOERR);
    int v, dim;
    std::size_t np, nv;
    nc_inq_dimid(id, "number_of_points", &dim);
    nc_inq_dimlen(id, dim, &np);
    nc_inq_dimid(id, "number_of_volumes", &dim);
    nc_inq_dimlen(id, dim, &nv);
    const SwwTestMesh mesh = readSwwTestMesh(id, np, nv);
    const auto &x = mesh.x, &y = mesh.y;
    const auto& tri = mesh.tri;
    const double xll = mesh.xll, yll = mesh.yll;
    std::vector<float> z(np);
    nc_inq_varid(id, "elevation", &v);
    int nd = 0;
    nc_inq_varndims(id, v, &nd);
    const std::size_t start[2] = {0, 0}, count[2] = {1, np};
    if (nd == 2)
        nc_get_vara_float(id, v, start, count, z.data());
    else
        nc_get_var_float(id, v, z.data());
    nc_close(id);
    const float zMin = *std::min_element(z.begin(), z.end());
    const float zMax = *std::max_element(z.begin(), z.end());
    EXPECT_NEAR(elev->minValue, zMin, 0.05 * (zMax - zMin) + 0.01);
    EXPECT_NEAR(elev->maxValue, zMax, 0.05 * (zMax - zMin) + 0.01);
    const double p = g.levels.back().pixelXSize;
    const int L = g.maxLevel();
    std::mt19937 rng(5);
    int checked = 0;
    for (int n = 0; n < 400 && checked < 150; ++n) {
        const std::size_t vi = std::size_t(tri[(rng() % nv) * 3]);
        const int gx = int((x[vi] + xll - g.minX) / p), gy = int((g.maxY - (y[vi] + yll)) / p);
        const double cx = g.minX + (gx + 0.5) * p - xll, cy = g.maxY - (gy + 0.5) * p - yll;
        const double expected =
            mesh.valueAt(cx, cy, [&](int i) { return double(z[std::size_t(i)]); });
        if (std::isnan(expected)) continue;
        auto tile = r->readElevation("elevation", TileId{L, gx / 256, gy / 256});
        ASSERT_TRUE(tile.ok()) << tile.diagnostics.format();
        // Within the store's quantisation of the bed's range.
        EXPECT_NEAR(tile->at(gx % 256, gy % 256), expected, 0.02 + 1e-4 * (zMax - zMin))
            << gx << "," << gy;
        ++checked;
    }
    EXPECT_GT(checked, 100);
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

namespace {

struct BadInput {
    const char* name;
    std::function<Diagnostics(const fs::path& dir, const fs::path& store)> run;
    const char* code;
    const char* message;
};

}  // namespace

TEST(ImportErrors, BadInputsTable) {
    const fs::path dir = testDir();
    const fs::path dem = makeDem(dir);
    const fs::path base = dir / "base.gpkg";
    ASSERT_FALSE(importElevation(dem.string(), options(base)).hasErrors());
    const double gt[6] = {550000, 30, 0, 5200000, 0, -30};
    writeTiff(dir / "nodata.tif", 50, 40, gt, 32610, std::vector<float>(2000, -5.f), -5.0);
    std::vector<float> withNan(2000, 3.f);
    withNan[777] = kNaN;
    writeTiff(dir / "nan.tif", 50, 40, gt, 32610, withNan);
    writeTiff(dir / "feet.tif", 50, 40, gt, 32610, std::vector<float>(2000, 100.f), std::nullopt,
              "ft");
    const double far[6] = {100000, 30, 0, 1000000, 0, -30};
    writeTiff(dir / "far.tif", 50, 40, far, 32610, std::vector<float>(2000, 1.f));
    { std::ofstream(dir / "text.tif") << "this is not a raster"; }
    // 446 bytes whose classic NetCDF header makes libnetcdf's nc_open ask for 7.6 GB for one
    // variable: found by SwwFuzzSmoke (tests/fuzz/CMakeLists.txt).
    fs::copy_file("tests/fuzz/seeds/sww/9d4e72bf320411a353c1a99efa4c2a6687fd2099",
                  dir / "header-bomb.sww");
    // 596 bytes whose variable of an unknown type made libnetcdf 4.9's nc_open divide by zero
    // (SIGFPE, the importer killed): found by SwwFuzzSmoke in a CI rehearsal.
    fs::copy_file("tests/fuzz/seeds/sww/96d676ae4d3a7c46781c640db9f0f7c05000ce02",
                  dir / "header-fpe.sww");
    GDALDatasetH png = GDALCreate(GDALGetDriverByName("MEM"), "", 8, 8, 1, GDT_Byte, nullptr);
    GDALClose(GDALCreateCopy(GDALGetDriverByName("PNG"), (dir / "bare.png").c_str(), png, 0,
                             nullptr, nullptr, nullptr));
    GDALClose(png);
    writeTiff(dir / "a_20240101T0000.tif", 50, 40, gt, 32610, std::vector<float>(2000, 1.f));
    writeTiff(dir / "b_20240101T0000.tif", 50, 40, gt, 32610, std::vector<float>(2000, 2.f));
    writeTiff(dir / "c_20231231T0000.tif", 50, 40, gt, 32610, std::vector<float>(2000, 2.f));

    auto elev = [](const char* file, std::function<void(ImportOptions&)> tweak = {}) {
        return [=](const fs::path& d, const fs::path& store) {
            ImportOptions o = options(store);
            o.name = "second";
            if (tweak) tweak(o);
            return importElevation((d / file).string(), o);
        };
    };
    auto seq = [](std::vector<std::string> files) {
        return [=](const fs::path& d, const fs::path& store) {
            ImportOptions o = options(store);
            o.name = "s";
            std::vector<std::string> paths;
            for (const auto& f : files) paths.push_back((d / f).string());
            return importSequence(paths, o);
        };
    };
    const BadInput cases[] = {
        {"missing file", elev("nope.tif"), "IMPORT_UNREADABLE", "nope.tif: cannot read raster"},
        {"not a raster", elev("text.tif"), "IMPORT_UNREADABLE", "text.tif: cannot read raster"},
        {"SWW header claiming gigabytes", elev("header-bomb.sww"), "IMPORT_UNREADABLE",
         "header-bomb.sww: cannot read SWW"},
        {"SWW header that made nc_open divide by zero", elev("header-fpe.sww"),
         "IMPORT_UNREADABLE", "header-fpe.sww: cannot read SWW: header gives a variable the unknown type"},
        {"no georeferencing", elev("bare.png"), "IMPORT_NO_GEOREF",
         "bare.png: source has no georeferencing"},
        {"all nodata", elev("nodata.tif"), "IMPORT_ALL_NODATA",
         "nodata.tif: source holds no valid value"},
        {"NaN values", elev("nan.tif"), "IMPORT_NAN",
         "nan.tif: row 15: source contains NaN values"},
        {"declared feet, told metres", elev("feet.tif", [](ImportOptions& o) { o.units = "m"; }),
         "IMPORT_UNITS_MISMATCH", "feet.tif: source declares its values in 'ft' but --units m"},
        {"outside the store", elev("far.tif"), "IMPORT_EXTENT_MISMATCH", "far.tif: source extent"},
        {"bad CRS", elev("far.tif", [](ImportOptions& o) { o.crs = "EPSG:99999999"; }),
         "IMPORT_BAD_CRS", "unknown CRS 'EPSG:99999999'"},
        {"existing layer name",
         elev("far.tif",
              [](ImportOptions& o) {
                  o.name = "elevation";
                  o.crs.reset();
              }),
         "IMPORT_EXTENT_MISMATCH", "far.tif"},
        {"duplicate timestamps", seq({"a_20240101T0000.tif", "b_20240101T0000.tif"}),
         "IMPORT_TIMES_DUPLICATE",
         "b_20240101T0000.tif: frame 1: duplicate timestamp 2024-01-01T00:00:00Z"},
        {"unsorted timestamps", seq({"a_20240101T0000.tif", "c_20231231T0000.tif"}),
         "IMPORT_TIMES_UNSORTED",
         "c_20231231T0000.tif: frame 1: timestamp 2023-12-31T00:00:00Z is earlier"},
        {"no timestamps", seq({"nan.tif"}), "IMPORT_NO_TIMES",
         "nan.tif: no timestamp for this frame"},
    };
    const std::string original = fileBytes(base);
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path store = dir / "case.gpkg";
        fs::copy_file(base, store, fs::copy_options::overwrite_existing);
        Diagnostics d = c.run(dir, store);
        ASSERT_TRUE(d.hasErrors()) << d.format();
        EXPECT_EQ(d.firstError()->code, c.code) << d.format();
        EXPECT_NE(d.firstError()->format().find(c.message), std::string::npos) << d.format();
        EXPECT_EQ(fileBytes(store), original);
        EXPECT_TRUE(leftovers(dir).empty());
    }
}

TEST(ImportErrors, FailureMidImportLeavesTheStoreUntouched) {
    const fs::path dir = testDir();
    const fs::path dem = makeDem(dir);
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(dem.string(), options(store)).hasErrors());
    const std::string before = fileBytes(store);
    ImportOptions o = options(store);
    o.name = "again";
    o.failAfterTiles = 5;
    Diagnostics d = importElevation(dem.string(), o);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_EQ(d.firstError()->code, "IMPORT_INJECTED_FAILURE");
    EXPECT_EQ(fileBytes(store), before);
    EXPECT_TRUE(leftovers(dir).empty());
    auto r = openStore(store);
    EXPECT_EQ(r->info().findLayer("again"), nullptr);

    // A new store that fails is not created at all.
    const fs::path fresh = dir / "fresh.gpkg";
    ImportOptions f = options(fresh);
    f.failAfterTiles = 2;
    EXPECT_TRUE(importElevation(dem.string(), f).hasErrors());
    EXPECT_FALSE(fs::exists(fresh));
    EXPECT_TRUE(leftovers(dir).empty());
}

TEST(ImportCommand, ExitCodes) {
    const fs::path dir = testDir();
    const fs::path dem = makeDem(dir);
    const std::string store = (dir / "s.gpkg").string();
    EXPECT_EQ(app::runImportCommand({}), 2);
    EXPECT_EQ(app::runImportCommand({"elevaton", dem.string(), "--store", store}), 2);
    EXPECT_EQ(app::runImportCommand({"elevation", dem.string()}), 2);
    EXPECT_EQ(
        app::runImportCommand({"elevation", dem.string(), "--store", store, "--pixel-sise", "3"}),
        2);
    EXPECT_EQ(
        app::runImportCommand({"elevation", dem.string(), "--store", store, "--z-scale", "abc"}),
        2);
    EXPECT_EQ(app::runImportCommand({"imagery", dem.string(), "--store", store}), 2);
    EXPECT_EQ(
        app::runImportCommand({"elevation", (dir / "missing.tif").string(), "--store", store}), 1);
    EXPECT_FALSE(fs::exists(store));
    EXPECT_EQ(app::runImportCommand({"elevation", dem.string(), "--store", store, "--quiet"}), 0);
    EXPECT_EQ(app::runInfoCommand({store}), 0);
    EXPECT_EQ(app::runInfoCommand({store, "--json"}), 0);
    EXPECT_EQ(app::runInfoCommand({(dir / "nothing.gpkg").string()}), 1);
    EXPECT_EQ(app::runInfoCommand({}), 2);
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
