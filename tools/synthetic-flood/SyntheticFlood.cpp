// make-synthetic-flood: a SYNTHETIC flood for the demo, derived from a DEM (no model behind it).
//
// Water rises in the basin of the lowest valid cell: at step k the water level is
// minElevation + rise * k / (steps - 1); a cell is wet when it is below that level AND connected
// (4-neighbour) to the seed through cells below it (a "bathtub" fill, not hydraulics). Depth =
// level - elevation on wet cells, nodata elsewhere. Writes steps GeoTIFFs (Float32, the DEM's
// grid and CRS) and times.csv (file,time) with irregular spacing so the demo exercises
// interpolation between unevenly spaced frames.
//
// usage: make-synthetic-flood DEM OUTDIR [--steps N] [--rise METRES] [--start ISO8601]
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <queue>
#include <string>
#include <vector>

#include "runtime/core/TimeParse.h"

namespace {

int fail(const std::string& msg) {
    std::fprintf(stderr, "make-synthetic-flood: %s\n", msg.c_str());
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3)
        return fail("usage: make-synthetic-flood DEM OUTDIR [--steps N] [--rise M] [--start ISO8601]"), 2;
    const std::string demPath = argv[1];
    const std::filesystem::path outDir = argv[2];
    int steps = 13;
    double rise = 150.0;
    std::string start = "2026-03-14T00:00:00Z";
    for (int i = 3; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--steps")) steps = std::max(2, std::atoi(argv[i + 1]));
        else if (!std::strcmp(argv[i], "--rise")) rise = std::atof(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--start")) start = argv[i + 1];
        else return fail(std::string("unknown option ") + argv[i]), 2;
    }
    const auto startEpoch = kiosk::parseIso8601(start);
    if (!startEpoch) return fail("--start wants an ISO 8601 UTC time");
    GDALAllRegister();
    GDALDataset* src = GDALDataset::FromHandle(GDALOpen(demPath.c_str(), GA_ReadOnly));
    if (!src) return fail(demPath + ": cannot open (" + CPLGetLastErrorMsg() + ")");
    const int w = src->GetRasterXSize(), h = src->GetRasterYSize();
    GDALRasterBand* band = src->GetRasterBand(1);
    int hasNodata = 0;
    const double nodata = band->GetNoDataValue(&hasNodata);
    std::vector<float> z(std::size_t(w) * std::size_t(h));
    if (band->RasterIO(GF_Read, 0, 0, w, h, z.data(), w, h, GDT_Float32, 0, 0) != CE_None)
        return fail(demPath + ": cannot read band 1");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::size_t seed = 0;
    float zmin = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < z.size(); ++i) {
        if (hasNodata && double(z[i]) == nodata) z[i] = nan;
        if (!std::isnan(z[i]) && z[i] < zmin) {
            zmin = z[i];
            seed = i;
        }
    }
    if (zmin == std::numeric_limits<float>::max()) return fail(demPath + ": all cells are nodata");
    // Fill level at which each cell first gets wet (priority flood from the seed): a cell is
    // wet at level L iff its "spill" elevation <= L. Then every step is one threshold.
    std::vector<float> spill(z.size(), std::numeric_limits<float>::infinity());
    using Item = std::pair<float, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
    spill[seed] = z[seed];
    q.push({z[seed], seed});
    const float limit = zmin + float(rise);
    while (!q.empty()) {
        auto [level, i] = q.top();
        q.pop();
        if (level > spill[i] || level > limit) continue;
        const int x = int(i % std::size_t(w)), y = int(i / std::size_t(w));
        const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
        for (int k = 0; k < 4; ++k) {
            if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
            const std::size_t j = std::size_t(ny[k]) * std::size_t(w) + std::size_t(nx[k]);
            if (std::isnan(z[j])) continue;
            const float s = std::max(level, z[j]);
            if (s < spill[j]) {
                spill[j] = s;
                q.push({s, j});
            }
        }
    }
    std::filesystem::create_directories(outDir);
    std::ofstream csv(outDir / "times.csv");
    csv << "file,time\n";
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    double geo[6];
    src->GetGeoTransform(geo);
    std::vector<float> depth(z.size());
    double t = *startEpoch;
    for (int k = 0; k < steps; ++k) {
        // Step 0 already holds a little water: a store rejects an all-nodata frame.
        const float level = zmin + 0.5f + (float(rise) - 0.5f) * float(k) / float(steps - 1);
        for (std::size_t i = 0; i < z.size(); ++i)
            depth[i] = (spill[i] <= level && z[i] < level) ? level - z[i] : nan;
        char name[32];
        std::snprintf(name, sizeof name, "flood_%03d.tif", k);
        const std::string path = (outDir / name).string();
        GDALDataset* dst = gtiff->Create(path.c_str(), w, h, 1, GDT_Float32, nullptr);
        if (!dst) return fail(path + ": cannot create");
        dst->SetGeoTransform(geo);
        dst->SetProjection(src->GetProjectionRef());
        GDALRasterBand* b = dst->GetRasterBand(1);
        b->SetNoDataValue(std::nan(""));
        b->SetUnitType("m");
        if (b->RasterIO(GF_Write, 0, 0, w, h, depth.data(), w, h, GDT_Float32, 0, 0) != CE_None)
            return fail(path + ": cannot write");
        GDALClose(dst);
        csv << name << "," << kiosk::formatIso8601(t) << "\n";
        // Irregular spacing: 30, 45, 60, 30, ... minutes.
        static const int minutes[] = {30, 45, 60};
        t += 60.0 * minutes[k % 3];
    }
    GDALClose(src);
    std::printf("make-synthetic-flood: %d frames in %s (SYNTHETIC: bathtub fill of the lowest basin, "
                "+%.0f m)\n", steps, outDir.c_str(), rise);
    return 0;
}
