// Curvilinear NetCDF (2-D lat/lon coordinate variables, as radar rainfall products ship) imports
// through GDAL's geolocation arrays: the test writes such a file with libnetcdf, imports it and
// checks that every stored sample holds the value of the source pixel at its own longitude and
// latitude (frame 0 holds the column index, frame 1 the row index, so a value *is* a position).
#include "runtime/import/Curvilinear.h"
#include "runtime/import/GdalRaster.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <netcdf.h>
#include <vector>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import;
using namespace kiosk::import::test;

namespace {

constexpr int kNx = 40, kNy = 30;

// The grid's lon/lat of source pixel (column i, row j): rotated and bent, so no geotransform
// describes it (columns curve with j^2).
double lonOf(double i, double j) {
    return 8.0 + 0.02 * i + 0.006 * j + 1e-4 * j * j;
}
double latOf(double i, double j) {
    return 47.0 - 0.004 * i - 0.015 * j;
}

// Source pixel (i, j) at lon/lat: Newton on the two equations above (exact to 1e-9 px).
void pixelAt(double lon, double lat, double& i, double& j) {
    i = kNx / 2.0, j = kNy / 2.0;
    for (int k = 0; k < 20; ++k) {
        const double f = lonOf(i, j) - lon, g = latOf(i, j) - lat;
        const double a = 0.02, b = 0.006 + 2e-4 * j, c = -0.004, d = -0.015;
        const double det = a * d - b * c;
        i -= (d * f - b * g) / det;
        j -= (-c * f + a * g) / det;
    }
}

// rain(time, y, x) with coordinates "lat lon" and 2-D lat(y, x) / lon(y, x); frame 0 = i,
// frame 1 = j.
void writeCurvilinear(const fs::path& p) {
    int id, dt, dy, dx, vt, vlat, vlon, vr;
    ASSERT_EQ(nc_create(p.c_str(), NC_CLOBBER, &id), NC_NOERR);
    nc_def_dim(id, "time", 2, &dt);
    nc_def_dim(id, "y", kNy, &dy);
    nc_def_dim(id, "x", kNx, &dx);
    nc_def_var(id, "time", NC_DOUBLE, 1, &dt, &vt);
    const int d2[2] = {dy, dx}, d3[3] = {dt, dy, dx};
    nc_def_var(id, "lat", NC_DOUBLE, 2, d2, &vlat);
    nc_def_var(id, "lon", NC_DOUBLE, 2, d2, &vlon);
    nc_def_var(id, "rain", NC_FLOAT, 3, d3, &vr);
    const char* tu = "hours since 2024-01-01 00:00:00";
    nc_put_att_text(id, vt, "units", std::strlen(tu), tu);
    nc_put_att_text(id, vlat, "units", 13, "degrees_north");
    nc_put_att_text(id, vlon, "units", 12, "degrees_east");
    nc_put_att_text(id, vlat, "standard_name", 8, "latitude");
    nc_put_att_text(id, vlon, "standard_name", 9, "longitude");
    nc_put_att_text(id, vr, "coordinates", 7, "lat lon");
    nc_put_att_text(id, vr, "units", 4, "mm/h");
    ASSERT_EQ(nc_enddef(id), NC_NOERR);
    const double t[2] = {0, 1};
    std::vector<double> lat(kNx * kNy), lon(kNx * kNy);
    std::vector<float> v(2 * kNx * kNy);
    for (int j = 0; j < kNy; ++j)
        for (int i = 0; i < kNx; ++i) {
            lon[std::size_t(j * kNx + i)] = lonOf(i, j);
            lat[std::size_t(j * kNx + i)] = latOf(i, j);
            v[std::size_t(j * kNx + i)] = float(i);
            v[std::size_t(kNx * kNy + j * kNx + i)] = float(j);
        }
    nc_put_var_double(id, vt, t);
    nc_put_var_double(id, vlat, lat.data());
    nc_put_var_double(id, vlon, lon.data());
    nc_put_var_float(id, vr, v.data());
    ASSERT_EQ(nc_close(id), NC_NOERR);
}

struct Placement {
    int checked = 0, outside = 0;
    double worst = 0;  ///< source pixels between where a value is and where it belongs
};

// Where each stored sample of frames 0 (column) and 1 (row) says it is, against where it is.
Placement placement(io::StoreReader& r) {
    ToLonLat toLonLat(r.info().grid.crsWkt);
    std::vector<float> col;
    forEachSample(
        r, "rain", [&](double, double, float v) { col.push_back(v); }, 0);
    Placement p;
    std::size_t k = 0;
    forEachSample(
        r, "rain",
        [&](double x, double y, float row) {
            if (k >= col.size()) return;
            const float c = col[k++];
            double lon = x, lat = y, i, j;
            if (!toLonLat(lon, lat)) return;
            pixelAt(lon, lat, i, j);
            // A value only where the grid is (no smear past half a pixel out of its footprint).
            if (i < -1.0 || i > kNx || j < -1.0 || j > kNy) ++p.outside;
            // Bilinear needs four source neighbours: compare half a pixel in from the edge.
            if (i < 0.5 || i > kNx - 1.5 || j < 0.5 || j > kNy - 1.5) return;
            p.worst = std::max({p.worst, std::fabs(c - i), std::fabs(row - j)});
            ++p.checked;
        },
        1);
    EXPECT_EQ(k, col.size()) << "the two frames cover different samples";
    return p;
}

}  // namespace

TEST(CurvilinearImport, NetCdfWithTwoDimensionalLatLonLandsWhereItsArraysSay) {
    const fs::path dir = freshTestDir("geokiosk-curvilinear-import-test");
    const fs::path nc = dir / "radar.nc";
    writeCurvilinear(nc);
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    o.name = "rain";
    o.variable = "rain";
    const Diagnostics d = importSequence({nc.string()}, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    ASSERT_TRUE(r);
    // 8.0..9.0 E, 46.5..47.0 N: the UTM zone of the centre, 32N.
    EXPECT_NE(r->info().grid.crsName.find("32N"), std::string::npos) << r->info().grid.crsName;
    const auto* s = r->info().findSequence("rain");
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->frameTimes.size(), 2u);
    EXPECT_EQ(s->units, "mm/h");
    const Placement p = placement(*r);
    // The grid is 40 x 30 pixels of about 1.5 x 1.7 km; the store's pixels are of that size.
    EXPECT_GT(p.checked, 600);
    EXPECT_EQ(p.outside, 0);
    // GDAL's inverse of the arrays (backmap + refinement) against the exact Newton inverse.
    // Measured 0.002 source pixels (GDAL 3.6); a flipped or shifted grid is off by whole pixels.
    EXPECT_LE(p.worst, 0.02) << "a value landed away from its place";
}

TEST(CurvilinearImport, ArraysKeptOnDiskGiveTheSamePlacement) {
    const fs::path dir = freshTestDir("geokiosk-curvilinear-import-test");
    const fs::path nc = dir / "radar.nc";
    writeCurvilinear(nc);
    // What the importer chooses for arrays too large for a quarter of the budget.
    CPLSetConfigOption("GDAL_GEOLOC_USE_TEMP_DATASETS", "YES");
    ImportOptions o = options(dir / "s.gpkg");
    o.name = "rain";
    o.variable = "rain";
    const Diagnostics d = importSequence({nc.string()}, o);
    CPLSetConfigOption("GDAL_GEOLOC_USE_TEMP_DATASETS", nullptr);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(dir / "s.gpkg");
    ASSERT_TRUE(r);
    const Placement p = placement(*r);
    EXPECT_GT(p.checked, 600);
    EXPECT_EQ(p.outside, 0);
    EXPECT_LE(p.worst, 0.02);
}

TEST(CurvilinearImport, GeolocationWorkingSetIsBudgeted) {
    const fs::path dir = freshTestDir("geokiosk-curvilinear-import-test");
    const fs::path nc = dir / "radar.nc";
    writeCurvilinear(nc);
    initGdal();
    GDALDatasetH ds = GDALOpen(("NETCDF:\"" + nc.string() + "\":rain").c_str(), GA_ReadOnly);
    ASSERT_NE(ds, nullptr);
    auto inRam = geolocationOf(ds, std::int64_t(2) << 30, "radar.nc");
    ASSERT_TRUE(inRam.ok()) << inRam.diagnostics.format();
    ASSERT_TRUE(*inRam);
    const Geolocation& g = **inRam;
    EXPECT_EQ(g.pixels, kNx * kNy);
    EXPECT_NEAR(g.extent.west, 8.0, 1e-9);
    EXPECT_NEAR(g.extent.east, lonOf(kNx - 1, kNy - 1), 1e-9);
    EXPECT_NEAR(g.extent.south, latOf(kNx - 1, kNy - 1), 1e-9);
    EXPECT_NEAR(g.extent.north, 47.0, 1e-9);
    EXPECT_FALSE(g.onDisk);
    EXPECT_TRUE(geolocationWarpArgs(g).empty());
    // Arrays above a quarter of the budget go to GDAL's temporary datasets, a fixed cache.
    auto tight = geolocationOf(ds, g.bytes * 4 - 1, "radar.nc");
    ASSERT_TRUE(tight.ok() && *tight);
    EXPECT_TRUE((*tight)->onDisk);
    EXPECT_EQ(geolocationWarpArgs(**tight),
              (std::vector<std::string>{"-to", "GEOLOC_USE_TEMP_DATASETS=YES"}));
    GDALClose(ds);
    // A projected CRS cannot be assigned to longitude/latitude arrays.
    ImportOptions o = options(dir / "s.gpkg");
    o.name = "rain";
    o.variable = "rain";
    o.assignCrs = "EPSG:32632";
    const Diagnostics d = importSequence({nc.string()}, o);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_EQ(d.firstError()->code, "IMPORT_BAD_CRS") << d.format();
    EXPECT_EQ(d.firstError()->file, nc.string());
}
