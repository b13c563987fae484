#include "tools/synthetic-dem/SyntheticDem.h"

#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace kiosk::tools {

std::string writeSyntheticDem(const std::filesystem::path& out, const SyntheticDemOptions& o) {
    if (o.size < 2 || o.size > 65536) return "size must be 2..65536 posts";
    if (!(o.post > 0) || !(o.featureMetres > 0)) return "spacing and feature scale must be > 0";
    GDALAllRegister();
    char** co = nullptr;
    co = CSLSetNameValue(co, "TILED", "YES");
    co = CSLSetNameValue(co, "BIGTIFF", "IF_SAFER");
    const int n = o.size;
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), out.c_str(), n, n, 1, GDT_Float32, co);
    CSLDestroy(co);
    if (!ds) return out.string() + ": cannot create (" + CPLGetLastErrorMsg() + ")";
    double gt[6] = {o.west, o.post, 0, o.north, 0, -o.post};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, 32610);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    GDALSetRasterNoDataValue(b, -9999);
    const int strip = 256;
    std::vector<float> rows(std::size_t(n) * strip);
    std::uint32_t seed = 12345;
    std::string error;
    for (int y0 = 0; y0 < n && error.empty(); y0 += strip) {
        const int h = std::min(strip, n - y0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < n; ++x) {
                const double u = double(x) * o.post / o.featureMetres;
                const double v = double(y0 + y) * o.post / o.featureMetres;
                double z = 0, amp = 1500, f = 3;
                for (int oct = 0; oct < 6; ++oct, amp *= 0.45, f *= 2.1)
                    z += amp * std::sin(f * 6.28318 * u + oct) * std::cos(f * 5.1 * v + 2 * oct);
                seed = seed * 1664525u + 1013904223u;
                z += double(seed >> 8) / double(1u << 24) * o.noiseMetres;
                rows[std::size_t(y) * std::size_t(n) + std::size_t(x)] = float(2000 + z);
            }
        if (GDALRasterIO(b, GF_Write, 0, y0, n, h, rows.data(), n, h, GDT_Float32, 0, 0) != CE_None)
            error = out.string() + ": write failed (" + CPLGetLastErrorMsg() + ")";
    }
    GDALClose(ds);
    return error;
}

}  // namespace kiosk::tools
