// ANUGA SWW: depth and bed against the model file read directly with netCDF.
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

namespace {

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

}  // namespace

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
