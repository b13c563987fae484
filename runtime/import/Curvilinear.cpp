#include "runtime/import/Curvilinear.h"

#include <cpl_conv.h>
#include <cpl_string.h>

#include <filesystem>

namespace kiosk::import {

namespace {

// GDAL's C-array geolocation transformer: the two arrays as doubles, and a backmap (x, y,
// weight as floats) of about the arrays' size, so roughly 16 + 3 x 4 bytes a pixel; 40 leaves
// room for the backmap being larger than the arrays.
constexpr std::int64_t kBytesPerArrayPixel = 40;
// GDAL's on-disk variant caches 64 tiles of 256 x 256 per array: two double arrays and three
// float backmap bands.
constexpr std::int64_t kOnDiskCacheBytes = 64LL * 256 * 256 * (2 * 8 + 3 * 4);
// GDAL switches to temporary datasets by itself from this array size.
constexpr std::int64_t kGdalOnDiskPixels = 16LL * 1000 * 1000;

struct MinMax {
    double min = 0, max = 0;
};

std::optional<MinMax> arrayRange(const char* dataset, const char* band) {
    GDALDatasetH ds = GDALOpen(dataset, GA_ReadOnly);
    if (!ds) return std::nullopt;
    std::optional<MinMax> out;
    const int b = band ? std::atoi(band) : 1;
    if (b >= 1 && b <= GDALGetRasterCount(ds)) {
        double mm[2];
        // Exact (every value read once, row by row): the extent decides the target CRS.
        if (GDALComputeRasterMinMax(GDALGetRasterBand(ds, b), FALSE, mm) == CE_None)
            out = MinMax{mm[0], mm[1]};
    }
    GDALClose(ds);
    return out;
}

}  // namespace

Result<std::optional<Geolocation>> geolocationOf(GDALDatasetH ds, std::int64_t budget,
                                                 const std::string& sourceName) {
    double gt[6];
    if (GDALGetGeoTransform(ds, gt) == CE_None &&
        !(gt[0] == 0 && gt[1] == 1 && gt[3] == 0 && gt[5] == 1))
        return std::optional<Geolocation>();
    char** md = GDALGetMetadata(ds, "GEOLOCATION");
    const char* xds = CSLFetchNameValue(md, "X_DATASET");
    const char* yds = CSLFetchNameValue(md, "Y_DATASET");
    if (!xds || !yds) return std::optional<Geolocation>();
    Diagnostics d;
    Geolocation g;
    const char* srs = CSLFetchNameValue(md, "SRS");
    auto crs = srs && *srs ? crsFromUser(srs, "geolocation SRS") : Result<StoreCrs>(wgs84());
    if (!crs) {
        d.error("IMPORT_GEOLOCATION", sourceName, "",
                "the CRS of the geolocation arrays is not understood");
        return d;
    }
    g.crs = *crs;
    const auto x = arrayRange(xds, CSLFetchNameValue(md, "X_BAND"));
    const auto y = arrayRange(yds, CSLFetchNameValue(md, "Y_BAND"));
    if (!x || !y) {
        d.error("IMPORT_GEOLOCATION", sourceName, "",
                gdalError("cannot read the geolocation arrays (" + std::string(xds) + ", " +
                          std::string(yds) + ")"));
        return d;
    }
    g.extent = {x->min, x->max, y->min, y->max};
    if (isGeographicCrs(g.crs.wkt) && (x->min < -180.0 - 1e-6 || x->max > 360.0 + 1e-6 ||
                                       y->min < -90.0 - 1e-6 || y->max > 90.0 + 1e-6)) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "geolocation arrays span %.6g..%.6g, %.6g..%.6g, which is not "
                      "longitude/latitude",
                      x->min, x->max, y->min, y->max);
        d.error("IMPORT_GEOLOCATION", sourceName, "", buf);
        return d;
    }
    GDALDatasetH xd = GDALOpen(xds, GA_ReadOnly);
    if (xd) {
        g.pixels = std::int64_t(GDALGetRasterXSize(xd)) * GDALGetRasterYSize(xd);
        GDALClose(xd);
    }
    const std::int64_t inRam = g.pixels * kBytesPerArrayPixel;
    g.onDisk = g.pixels >= kGdalOnDiskPixels || inRam > budget / 4;
    g.bytes = g.onDisk ? kOnDiskCacheBytes : inRam;
    if (g.onDisk && !CPLGetConfigOption("CPL_TMPDIR", nullptr)) {
        // GDAL writes its temporary arrays to CPL_TMPDIR, else the working directory.
        std::error_code ec;
        const auto tmp = std::filesystem::temp_directory_path(ec);
        if (!ec) CPLSetConfigOption("CPL_TMPDIR", tmp.c_str());
    }
    return std::optional<Geolocation>(g);
}

std::vector<std::string> geolocationWarpArgs(const Geolocation& g) {
    std::vector<std::string> out;
    for (const auto& o : geolocationTransformerOptions(g)) out.insert(out.end(), {"-to", o});
    return out;
}

std::vector<std::string> geolocationTransformerOptions(const Geolocation& g) {
    // Only forced on: otherwise GDAL_GEOLOC_USE_TEMP_DATASETS (or GDAL's default) decides.
    if (g.onDisk) return {"GEOLOC_USE_TEMP_DATASETS=YES"};
    return {};
}

}  // namespace kiosk::import
