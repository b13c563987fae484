// Geographic inputs: non-square degree pixels in bounded memory, CF lon/lat NetCDF on 0..360
// across the dateline, whole-globe rolls and wraps past 360 degrees, the automatic target CRS,
// --assign-crs / --to-crs, multi-band refusal and the pre-flight memory budget.
#include "runtime/app/ImportCommand.h"
#include "runtime/import/Importer.h"
#include "runtime/io/StoreReader.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <netcdf.h>
#include <optional>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import;
using namespace kiosk::import::test;

namespace {

fs::path testDir() {
    return import::test::freshTestDir("geokiosk-geo-import-test");
}

// A GeoTIFF of `bands` Float32 (or Byte when `rgb`) bands filled by value(x, y).
void writeTiff(const fs::path& p, int w, int h, const double gt[6], int epsg,
               const std::function<float(int, int)>& value, int bands = 1, bool rgb = false) {
    GDALAllRegister();
    char** opts = nullptr;
    if (rgb) opts = CSLSetNameValue(opts, "PHOTOMETRIC", "RGB");
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), w, h, bands,
                                 rgb ? GDT_Byte : GDT_Float32, opts);
    CSLDestroy(opts);
    ASSERT_NE(ds, nullptr);
    GDALSetGeoTransform(ds, const_cast<double*>(gt));
    if (epsg) GDALSetProjection(ds, wktOf(epsg).c_str());
    std::vector<float> v(std::size_t(w) * std::size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            v[std::size_t(y) * std::size_t(w) + std::size_t(x)] = value(x, y);
    for (int b = 1; b <= bands; ++b)
        ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b), GF_Write, 0, 0, w, h, v.data(), w, h,
                               GDT_Float32, 0, 0),
                  CE_None);
    GDALClose(ds);
}

// A CF NetCDF elevation grid on lon/lat axes without any CRS (as global relief grids ship):
// longitudes lon0 + (i + 0.5) * step, latitudes ascending from lat0 (south first, as CF files
// usually are), z(lon, lat) in metres.
void writeLonLatNetCdf(const fs::path& p, double lon0, double lat0, double step, int nx, int ny,
                       const std::function<double(double, double)>& z) {
    int id, dlat, dlon, vlat, vlon, vz;
    ASSERT_EQ(nc_create(p.c_str(), NC_CLOBBER, &id), NC_NOERR);
    nc_def_dim(id, "lat", std::size_t(ny), &dlat);
    nc_def_dim(id, "lon", std::size_t(nx), &dlon);
    nc_def_var(id, "lat", NC_DOUBLE, 1, &dlat, &vlat);
    nc_def_var(id, "lon", NC_DOUBLE, 1, &dlon, &vlon);
    const int dims[2] = {dlat, dlon};
    nc_def_var(id, "z", NC_FLOAT, 2, dims, &vz);
    nc_put_att_text(id, vlon, "units", 12, "degrees_east");
    nc_put_att_text(id, vlat, "units", 13, "degrees_north");
    nc_put_att_text(id, vz, "units", 1, "m");
    nc_enddef(id);
    std::vector<double> lats(static_cast<std::size_t>(ny)), lons(static_cast<std::size_t>(nx));
    for (int j = 0; j < ny; ++j) lats[std::size_t(j)] = lat0 + (j + 0.5) * step;
    for (int i = 0; i < nx; ++i) lons[std::size_t(i)] = lon0 + (i + 0.5) * step;
    std::vector<float> v(std::size_t(nx) * std::size_t(ny));
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            v[std::size_t(j) * std::size_t(nx) + std::size_t(i)] =
                float(z(lons[std::size_t(i)], lats[std::size_t(j)]));
    nc_put_var_double(id, vlat, lats.data());
    nc_put_var_double(id, vlon, lons.data());
    nc_put_var_float(id, vz, v.data());
    nc_close(id);
}

// Run `fn` in a child process whose address space is capped at `limitBytes` (ulimit -v).
// Returns the child's exit status, or -signal when it died of one.
int runUnderAddressLimit(std::int64_t limitBytes, const std::function<int()>& fn) {
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        rlimit rl{rlim_t(limitBytes), rlim_t(limitBytes)};
        setrlimit(RLIMIT_AS, &rl);
        _exit(fn());
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

std::int64_t currentAddressSpace() {
    std::ifstream f("/proc/self/status");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind("VmSize:", 0) == 0) return std::int64_t(std::stoll(line.substr(7))) * 1024;
    return 0;
}

}  // namespace

// The reproduction: 94 x 90 px EPSG:4326, pixels 0.0084 x 0.0083 degrees. The importer
// used to pass the degree resolution together with the UTM target (~20 GB, then the OOM killer).
TEST(GeographicImport, NonSquareDegreePixelsInBoundedMemoryMatchGdalwarp) {
    const fs::path dir = testDir();
    const fs::path src = dir / "geo.tif";
    const double gt[6] = {-121.95, 0.0084, 0, 46.98, 0, -0.0083};
    writeTiff(src, 94, 90, gt, 4326, [](int x, int y) {
        return 1500.0f + 600.0f * std::sin(float(x) / 15.0f) * std::cos(float(y) / 11.0f);
    });
    const fs::path store = dir / "s.gpkg";
    // Address space of this process plus 768 MiB: ample for a 94 x 90 import, far below the
    // gigabytes the old resolution bug asked for.
    const std::int64_t limit = currentAddressSpace() + (std::int64_t(768) << 20);
    const int status = runUnderAddressLimit(limit, [&] {
        return app::runImportCommand(
            {"elevation", src.string(), "--store", store.string(), "--quiet", "--threads", "1"});
    });
    ASSERT_EQ(status, 0);
    auto r = openStore(store);
    ASSERT_TRUE(r);
    const auto& g = r->info().grid;
    EXPECT_EQ(g.srsId, 32610);  // UTM 10N, the zone of the centre
    const double p = g.levels.back().pixelXSize;
    EXPECT_GT(p, 500.0);  // about 640 m x 920 m source pixels: a metre pixel, not 0.0083 m
    EXPECT_LT(p, 950.0);

    if (!haveTool("gdalwarp")) GTEST_SKIP() << "gdalwarp not installed: comparison skipped";
    const fs::path ref = dir / "ref.tif";
    const std::string cmd =
        "gdalwarp -q -t_srs EPSG:32610 -r bilinear -ot Float32 -dstnodata nan '" + src.string() +
        "' '" + ref.string() + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    GDALDatasetH rd = GDALOpen(ref.c_str(), GA_ReadOnly);
    ASSERT_NE(rd, nullptr);
    double rgt[6];
    GDALGetGeoTransform(rd, rgt);
    const int rw = GDALGetRasterXSize(rd), rh = GDALGetRasterYSize(rd);
    std::vector<float> refv(std::size_t(rw) * std::size_t(rh));
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(rd, 1), GF_Read, 0, 0, rw, rh, refv.data(), rw, rh,
                           GDT_Float32, 0, 0),
              CE_None);
    GDALClose(rd);
    EXPECT_NEAR(rgt[1], p, 1e-6 * p);
    int compared = 0;
    double worst = 0;
    forEachSample(*r, "elevation", [&](double x, double y, float v) {
        const double fx = (x - rgt[0]) / rgt[1] - 0.5, fy = (y - rgt[3]) / rgt[5] - 0.5;
        const int ix = int(std::lround(fx)), iy = int(std::lround(fy));
        ASSERT_NEAR(fx, ix, 1e-6);
        ASSERT_NEAR(fy, iy, 1e-6);
        if (ix < 0 || iy < 0 || ix >= rw || iy >= rh) return;
        const float want = refv[std::size_t(iy) * std::size_t(rw) + std::size_t(ix)];
        if (std::isnan(want)) return;
        worst = std::max(worst, double(std::fabs(v - want)));
        ++compared;
    });
    EXPECT_GT(compared, 94 * 90 / 2);
    EXPECT_LE(worst, 0.5);
}

TEST(GeographicImport, PreflightRefusesAGridAboveTheMemoryBudget) {
    const fs::path dir = testDir();
    const fs::path src = dir / "thin.tif";
    // 10 x 10 pixels of 100 m x 1 mm: the square finest pixel (1 mm) makes a 10^6 px wide grid.
    const double gt[6] = {500000, 100, 0, 5000000, 0, -0.001};
    writeTiff(src, 10, 10, gt, 32610, [](int x, int y) { return float(x + y); });
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    Diagnostics d = importElevation(src.string(), o);
    ASSERT_TRUE(d.has("IMPORT_TOO_LARGE")) << d.format();
    EXPECT_NE(d.firstError()->message.find("budget"), std::string::npos);
    EXPECT_FALSE(fs::exists(store));
    // The same through the command, under an address-space cap: a clean exit 1, no signal.
    const std::int64_t limit = currentAddressSpace() + (std::int64_t(512) << 20);
    EXPECT_EQ(runUnderAddressLimit(limit,
                                   [&] {
                                       return app::runImportCommand(
                                           {"elevation", src.string(), "--store", store.string(),
                                            "--quiet", "--max-memory", "4096"});
                                   }),
              1);
}

// A wide CF lon/lat grid on 0..360 crossing the dateline (120E..120W): no CRS in the file, so the
// axes must be recognised as degrees; 120 degrees wide, so the store is a plate carrée in metres
// centred on 180 and the grid stays in one piece. z is linear in (continuous) longitude and
// latitude, which bilinear resampling reproduces exactly, so every stored sample must equal z at
// its own lon/lat within the quantisation step; a longitude wrap error would be a 7200 m spike.
TEST(GeographicImport, LonLatNetCdfOn0To360AcrossTheDateline) {
    const fs::path dir = testDir();
    const fs::path nc = dir / "relief.nc";
    auto z = [](double lon, double lat) { return 1000.0 + 20.0 * (lon - 120.0) + 10.0 * lat; };
    writeLonLatNetCdf(nc, 120.0, -30.0, 0.5, 240, 120, z);
    const fs::path store = dir / "s.gpkg";
    Diagnostics d = importElevation(nc.string(), options(store));
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    ASSERT_TRUE(r);
    const auto& g = r->info().grid;
    EXPECT_NE(g.crsWkt.find("Equirectangular"), std::string::npos) << g.crsWkt;
    EXPECT_NE(g.crsWkt.find("\"central_meridian\",-180]"), std::string::npos) << g.crsWkt;
    const io::LayerInfo* l = r->info().findLayer("elevation");
    ASSERT_NE(l, nullptr);
    ToLonLat toLonLat(g.crsWkt);
    int checked = 0;
    double worst = 0, lo = 1e9, hi = -1e9;
    forEachSample(*r, "elevation", [&](double x, double y, float v) {
        lo = std::min(lo, double(v));
        hi = std::max(hi, double(v));
        ASSERT_TRUE(toLonLat(x, y));
        double lon = x < 0 ? x + 360.0 : x;  // continuous 120..240
        // Bilinear needs a neighbour on each side: half a source pixel in from the border.
        if (lon < 120.25 || lon > 239.75 || y < -29.75 || y > 29.75) return;
        worst = std::max(worst, std::fabs(double(v) - z(lon, y)));
        ++checked;
    });
    EXPECT_GT(checked, 20000);
    EXPECT_LE(worst, l->precision);
    EXPECT_GE(lo, z(120.0, -30.0) - l->precision);  // no spike anywhere, border included
    EXPECT_LE(hi, z(240.0, 30.0) + l->precision);
}

// A whole-globe grid on 0..360 is rolled to -180..180 (here kept in degrees with --to-crs), and
// a regional one east of 180 is the same place 360 degrees west: UTM of its centre.
TEST(GeographicImport, GlobalGridIsRolledAndRegionalEastOf180IsShifted) {
    const fs::path dir = testDir();
    const fs::path global = dir / "global.nc";
    auto zg = [](double lon, double lat) { return std::floor(lon) * 10.0 + (lat + 90.0); };
    writeLonLatNetCdf(global, 0.0, -90.0, 1.0, 360, 180, zg);
    const fs::path gs = dir / "global.gpkg";
    ImportOptions o = options(gs);
    o.toCrs = "EPSG:4326";
    Diagnostics d = importElevation(global.string(), o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(gs);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->info().grid.srsId, 4326);
    EXPECT_DOUBLE_EQ(r->info().grid.minX, -180.0);
    EXPECT_DOUBLE_EQ(r->info().grid.maxY, 90.0);
    const double step = r->info().findLayer("elevation")->precision;
    int checked = 0;
    forEachSample(*r, "elevation", [&](double lon, double lat, float v) {
        if (lon > 180.0) return;  // the square tile matrix extends past the data
        const double src = lon < 0 ? lon + 360.0 : lon;
        EXPECT_NEAR(v, zg(src, lat), step / 2 + 1e-3) << lon << " " << lat;
        ++checked;
    });
    EXPECT_EQ(checked, 360 * 180);

    const fs::path regional = dir / "hawaii.nc";
    writeLonLatNetCdf(regional, 200.0, 18.0, 0.05, 100, 60,
                      [](double lon, double lat) { return 100.0 * (lon - 200.0) + lat; });
    const fs::path rs = dir / "hawaii.gpkg";
    d = importElevation(regional.string(), options(rs));
    ASSERT_FALSE(d.hasErrors()) << d.format();
    r = openStore(rs);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->info().grid.srsId, 32604);  // centre 202.5 E = 157.5 W: UTM zone 4 N
}

// Whole-globe grids that wrap past 360 degrees: ETOPO20 as Ferret ships it starts at 20 E and has
// one column more than the globe; model output on 0..360 often repeats the first column at the
// end. Each lands on -180..180 with the repeated column gone and every sample from its own
// meridian (z is a function of the wrapped longitude, so a misplaced column shows).
TEST(GeographicImport, GlobalGridsWrappingPast360AreNormalised) {
    const fs::path dir = testDir();
    auto wrapped = [](double lon) { return lon - 360.0 * std::floor(lon / 360.0); };
    auto zg = [&](double lon, double lat) { return std::floor(wrapped(lon)) * 10.0 + lat + 90.0; };
    struct Case {
        const char* name;
        double lon0;  // west edge; centres at lon0 + (i + 0.5) * step
        int columns;
        double step = 1.0;
    };
    for (const Case& c :
         {Case{"etopo-like", 20.0, 361}, Case{"etopo20-spacing", 20.0, 1081, 1.0 / 3.0},
          Case{"repeated-0-360", -0.5, 361}, Case{"from-200-west", -200.0, 360},
          Case{"halo", -1.0, 362}}) {
        SCOPED_TRACE(c.name);
        const fs::path nc = dir / (std::string(c.name) + ".nc");
        const int rows = int(std::lround(180.0 / c.step));
        writeLonLatNetCdf(nc, c.lon0, -90.0, c.step, c.columns, rows, zg);
        const fs::path store = dir / (std::string(c.name) + ".gpkg");
        ImportOptions o = options(store);
        o.toCrs = "EPSG:4326";
        Diagnostics d = importElevation(nc.string(), o);
        ASSERT_FALSE(d.hasErrors()) << d.format();
        auto r = openStore(store);
        ASSERT_TRUE(r);
        const io::LayerInfo* l = r->info().findLayer("elevation");
        ASSERT_NE(l, nullptr);
        // One turn of columns from the column whose centre is nearest above -180.
        EXPECT_NEAR(l->dataMaxX - l->dataMinX, 360.0, 1e-9);
        EXPECT_GE(l->dataMinX, -180.5 - 1e-9);
        EXPECT_LE(l->dataMinX, -180.0 + 1e-9);
        int checked = 0;
        forEachSample(*r, "elevation", [&](double lon, double lat, float v) {
            if (lon > l->dataMaxX || lon < l->dataMinX) return;  // the tile matrix's padding
            EXPECT_NEAR(v, zg(lon, lat), l->precision / 2 + 1e-3) << lon << " " << lat;
            ++checked;
        });
        EXPECT_EQ(checked, int(std::lround(360.0 / c.step)) * rows);
    }
    // Without --to-crs the globe goes to the global projection, as any whole-globe grid.
    const fs::path store = dir / "etopo-4087.gpkg";
    Diagnostics d = importElevation((dir / "etopo-like.nc").string(), options(store));
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->info().grid.srsId, 4087);
    const io::LayerInfo* l = r->info().findLayer("elevation");
    ASSERT_NE(l, nullptr);
    EXPECT_NEAR(l->dataMinX, -20037508.34, 1.0);
    EXPECT_NEAR(l->dataMaxX, 20037508.34, 1.0);
}

TEST(GeographicImport, CrsOptionsAndMultiBandRefusal) {
    const fs::path dir = testDir();
    const fs::path nc = dir / "relief.nc";
    writeLonLatNetCdf(nc, 10.0, 40.0, 0.01, 50, 40,
                      [](double lon, double lat) { return 100.0 * lon + lat; });
    const std::string store = (dir / "s.gpkg").string();
    // Degrees cannot be Web Mercator metres.
    EXPECT_EQ(app::runImportCommand({"elevation", nc.string(), "--store", store, "--assign-crs",
                                     "EPSG:3857", "--quiet"}),
              1);
    EXPECT_FALSE(fs::exists(store));
    ImportOptions o = options(store);
    o.assignCrs = "EPSG:3857";
    Diagnostics d = importElevation(nc.string(), o);
    ASSERT_TRUE(d.has("IMPORT_BAD_CRS")) << d.format();
    EXPECT_EQ(d.firstError()->where, "--assign-crs");
    // --to-crs reprojects; the deprecated --crs still means "to" for a source with a CRS.
    EXPECT_EQ(app::runImportCommand(
                  {"elevation", nc.string(), "--store", store, "--to-crs", "EPSG:3857", "--quiet"}),
              0);
    EXPECT_EQ(openStore(store)->info().grid.srsId, 3857);
    fs::remove(store);
    EXPECT_EQ(app::runImportCommand(
                  {"elevation", nc.string(), "--store", store, "--crs", "EPSG:32632", "--quiet"}),
              0);
    EXPECT_EQ(openStore(store)->info().grid.srsId, 32632);
    EXPECT_EQ(app::runImportCommand({"elevation", nc.string(), "--store", store, "--crs",
                                     "EPSG:32632", "--to-crs", "EPSG:32632"}),
              2);

    // An RGB GeoTIFF is not an elevation model unless a band is named.
    const fs::path rgb = dir / "rgb.tif";
    const double gt[6] = {500000, 10, 0, 5000000, 0, -10};
    writeTiff(
        rgb, 40, 30, gt, 32632, [](int x, int y) { return float(x * 3 + y); }, 3, true);
    const std::string s2 = (dir / "s2.gpkg").string();
    ImportOptions o2 = options(s2);
    d = importElevation(rgb.string(), o2);
    ASSERT_TRUE(d.has("IMPORT_MULTIBAND")) << d.format();
    EXPECT_NE(d.firstError()->message.find("Red"), std::string::npos) << d.format();
    EXPECT_EQ(app::runImportCommand({"elevation", rgb.string(), "--store", s2, "--band", "4"}), 1);
    EXPECT_EQ(app::runImportCommand({"elevation", rgb.string(), "--store", s2, "--band", "x"}), 2);
    EXPECT_EQ(
        app::runImportCommand({"elevation", rgb.string(), "--store", s2, "--band", "2", "--quiet"}),
        0);
}
