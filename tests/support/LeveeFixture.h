#pragma once

// Test data for the local TINs (issue 20, Baumann et al. 2000): a small DEM (UTM 10N, 1 m posts)
// of a gentle slope with one sharp levee along a diagonal whose crest falls between posts, and a
// GeoJSON line along the crest with the crest's true height (3D) or without (2D). Written by
// the tests, header-only (GDAL's C API).
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace kiosk::test::levee {

constexpr int kWidth = 480, kHeight = 400;          // pixels (1 m)
constexpr double kX0 = 550000.0, kY1 = 5200000.0;   // north-west corner
constexpr double kHeightM = 3.0, kHalfWidth = 5.0;  // levee height and half base width
// Crest end points (world): a diagonal that no post row, column or diagonal follows.
constexpr double kAx = kX0 + 60.3, kAy = kY1 - 70.7, kBx = kX0 + 420.2, kBy = kY1 - 330.9;

inline double ground(double x, double y) {
    return 20.0 + 0.01 * (x - kX0) + 0.005 * (kY1 - y);
}
inline double crestDistance(double x, double y) {
    const double dx = kBx - kAx, dy = kBy - kAy;
    const double t = std::clamp(((x - kAx) * dx + (y - kAy) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    return std::hypot(x - (kAx + t * dx), y - (kAy + t * dy));
}
/** @brief The true surface: the slope plus a levee of triangular section. */
inline double surface(double x, double y) {
    return ground(x, y) + kHeightM * std::max(0.0, 1.0 - crestDistance(x, y) / kHalfWidth);
}
inline double crestHeight(double x, double y) {
    return ground(x, y) + kHeightM;
}

/** @brief The DEM as a GeoTIFF (posts = pixel centres sampled from surface()). */
inline std::filesystem::path writeDem(const std::filesystem::path& dir) {
    std::vector<float> v(std::size_t(kWidth) * kHeight);
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i)
            v[std::size_t(j) * kWidth + std::size_t(i)] =
                float(surface(kX0 + i + 0.5, kY1 - j - 0.5));
    GDALAllRegister();
    const std::filesystem::path p = dir / "levee.tif";
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), kWidth, kHeight, 1,
                                 GDT_Float32, nullptr);
    double gt[6] = {kX0, 1.0, 0.0, kY1, 0.0, -1.0};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH utm = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(utm, 32610);  // UTM 10N
    GDALSetSpatialRef(ds, utm);
    OSRDestroySpatialReference(utm);
    CPLErr e = GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, kWidth, kHeight, v.data(),
                            kWidth, kHeight, GDT_Float32, 0, 0);
    (void)e;
    GDALClose(ds);
    return p;
}

/** @brief The crest as GeoJSON in UTM 10N: with the crest's height (3D) or without (2D). */
inline std::filesystem::path writeCrest(const std::filesystem::path& dir, bool withZ,
                                        const std::string& name = "crest.geojson") {
    const std::filesystem::path p = dir / name;
    std::ofstream f(p);
    f.precision(12);
    f << R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32610"}},)"
      << R"("features":[{"type":"Feature","properties":{"name":"levee"},"geometry":{"type":"LineString","coordinates":[)";
    auto point = [&](double x, double y) {
        f << "[" << x << "," << y;
        if (withZ) f << "," << crestHeight(x, y);
        f << "]";
    };
    point(kAx, kAy);
    f << ",";
    point(kBx, kBy);
    f << "]}}]}\n";
    return p;
}

}  // namespace kiosk::test::levee
