#include "runtime/import/GdalRaster.h"

#include "runtime/import/Curvilinear.h"
#include "runtime/import/GeoTarget.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_utils.h>
#include <gdalwarper.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>

namespace kiosk::import {

namespace {

struct SrsDeleter {
    void operator()(void* h) const noexcept {
        if (h) OSRDestroySpatialReference(OGRSpatialReferenceH(h));
    }
};
using Srs = std::unique_ptr<void, SrsDeleter>;

StoreCrs describe(OGRSpatialReferenceH srs) {
    StoreCrs c;
    const char* auth = OSRGetAuthorityName(srs, nullptr);
    const char* code = OSRGetAuthorityCode(srs, nullptr);
    if (auth && code && std::strcmp(auth, "EPSG") == 0) c.srsId = std::atoi(code);
    const char* name = OSRGetName(srs);
    c.name = name ? name : "unnamed";
    char* wkt = nullptr;
    if (OSRExportToWkt(srs, &wkt) == OGRERR_NONE && wkt) c.wkt = wkt;
    CPLFree(wkt);
    if (c.srsId <= 0) c.srsId = 100001;  // a custom CRS row of this store
    return c;
}

Srs srsFromWkt(const std::string& wkt) {
    Srs s(OSRNewSpatialReference(nullptr));
    OSRSetAxisMappingStrategy(OGRSpatialReferenceH(s.get()), OAMS_TRADITIONAL_GIS_ORDER);
    if (OSRSetFromUserInput(OGRSpatialReferenceH(s.get()), wkt.c_str()) != OGRERR_NONE)
        return nullptr;
    return s;
}

}  // namespace

bool sameCrs(const std::string& a, const std::string& b) {
    if (a == b) return true;
    Srs sa = srsFromWkt(a), sb = srsFromWkt(b);
    if (!sa || !sb) return false;
    return OSRIsSame(OGRSpatialReferenceH(sa.get()), OGRSpatialReferenceH(sb.get())) != 0;
}

bool isGeographicCrs(const std::string& wkt) {
    Srs s = srsFromWkt(wkt);
    return s && OSRIsGeographic(OGRSpatialReferenceH(s.get()));
}

void initGdal() {
    static std::once_flag once;
    std::call_once(once, [] {
        GDALAllRegister();
        CPLPushErrorHandler(CPLQuietErrorHandler);
        // Bounded memory: the default cache is 5 % of RAM, far above our import budget.
        GDALSetCacheMax64(GIntBig(96) * 1024 * 1024);
    });
}

std::string gdalError(const std::string& fallback) {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? fallback + ": " + m : fallback;
}

Result<GdalDataset> openRaster(const std::string& path) {
    initGdal();
    CPLErrorReset();
    GDALDatasetH h =
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR, nullptr,
                   nullptr, nullptr);
    if (!h) {
        Diagnostics d;
        d.error("IMPORT_UNREADABLE", path, "", gdalError("cannot read raster"));
        return d;
    }
    if (GDALGetRasterCount(h) < 1) {
        GDALClose(h);
        Diagnostics d;
        d.error("IMPORT_UNREADABLE", path, "",
                "no raster band (for NetCDF name the variable with --variable)");
        return d;
    }
    return GdalDataset(h);
}

StoreCrs localCrs() {
    StoreCrs c;
    c.srsId = 100000;
    c.name = "geokiosk local metres";
    c.wkt =
        "LOCAL_CS[\"geokiosk local metres\",LOCAL_DATUM[\"geokiosk\",0],UNIT[\"metre\",1],"
        "AXIS[\"Easting\",EAST],AXIS[\"Northing\",NORTH]]";
    return c;
}

Result<StoreCrs> crsFromUser(const std::string& text, const std::string& option) {
    initGdal();
    Srs s(OSRNewSpatialReference(nullptr));
    if (OSRSetFromUserInput(OGRSpatialReferenceH(s.get()), text.c_str()) != OGRERR_NONE) {
        Diagnostics d;
        d.error("IMPORT_BAD_CRS", "", option, "unknown CRS '" + text + "'");
        return d;
    }
    return describe(OGRSpatialReferenceH(s.get()));
}

std::optional<StoreCrs> crsOfDataset(GDALDatasetH ds) {
    OGRSpatialReferenceH s = GDALGetSpatialRef(ds);
    if (!s) return std::nullopt;
    return describe(s);
}

StoreCrs utmCrsFor(double lon, double lat) {
    const int zone = std::clamp(int(std::floor((lon + 180.0) / 6.0)) + 1, 1, 60);
    auto c = crsFromUser("EPSG:" + std::to_string((lat >= 0 ? 32600 : 32700) + zone));
    return c ? *c : localCrs();
}

double chooseScale(double range, double minStep) {
    const double need = std::max(minStep, range * 1.5 / 65534.0);
    return std::exp2(std::ceil(std::log2(std::max(need, 1e-9))));
}

std::optional<std::pair<double, double>> bandRange(GDALDatasetH ds, int band) {
    GDALRasterBandH b = GDALGetRasterBand(ds, band);
    double mm[2] = {0, 0};
    CPLErrorReset();
    // Exact up to 64 Mpixel (one extra read, cheap next to encoding); sampled above that, where
    // chooseScale's margin absorbs what sampling misses.
    const bool approx = double(GDALGetRasterXSize(ds)) * GDALGetRasterYSize(ds) > 64e6;
    if (GDALComputeRasterMinMax(b, approx, mm) != CE_None || !std::isfinite(mm[0])) {
        CPLErrorReset();
        if (GDALComputeRasterMinMax(b, FALSE, mm) != CE_None || !std::isfinite(mm[0]))
            return std::nullopt;
    }
    const double s = GDALGetRasterScale(b, nullptr), o = GDALGetRasterOffset(b, nullptr);
    double a = mm[0] * s + o, z = mm[1] * s + o;
    if (a > z) std::swap(a, z);
    return std::make_pair(a, z);
}

GdalDataset memRaster(const std::vector<float>& values, int width, int height,
                      const std::array<double, 6>& gt, const std::string& wkt,
                      std::optional<double> nodata) {
    initGdal();
    GDALDriverH mem = GDALGetDriverByName("MEM");
    GDALDatasetH ds = GDALCreate(mem, "", width, height, 1, GDT_Float32, nullptr);
    if (!ds) return nullptr;
    double g[6];
    std::copy(gt.begin(), gt.end(), g);
    GDALSetGeoTransform(ds, g);
    if (!wkt.empty()) GDALSetProjection(ds, wkt.c_str());
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    if (nodata) GDALSetRasterNoDataValue(b, *nodata);
    if (GDALRasterIO(b, GF_Write, 0, 0, width, height, const_cast<float*>(values.data()), width,
                     height, GDT_Float32, 0, 0) != CE_None) {
        GDALClose(ds);
        return nullptr;
    }
    return GdalDataset(ds);
}

ScalarRowSource scalarRows(const PlacedSource& p, int band, double factor,
                           const std::string& sourceName) {
    GDALDatasetH ds = p.ds;
    const int xOff = p.xOff, yOff = p.yOff, width = p.window.width();
    return [=](int row0, int rows, float* out) -> Diagnostics {
        Diagnostics d;
        GDALRasterBandH b = GDALGetRasterBand(ds, band);
        int hasNodata = 0;
        const double nodata = GDALGetRasterNoDataValue(b, &hasNodata);
        const double scale = GDALGetRasterScale(b, nullptr) * factor;
        const double offset = GDALGetRasterOffset(b, nullptr) * factor;
        std::vector<double> buf(std::size_t(width) * std::size_t(rows));
        CPLErrorReset();
        if (GDALRasterIO(b, GF_Read, xOff, yOff + row0, width, rows, buf.data(), width, rows,
                         GDT_Float64, 0, 0) != CE_None) {
            d.error("IMPORT_READ", sourceName, "", gdalError("cannot read rows"));
            return d;
        }
        const bool nanIsNodata = hasNodata && std::isnan(nodata);
        const bool warped =
            GDALGetDatasetDriver(ds) &&
            std::strcmp(GDALGetDriverShortName(GDALGetDatasetDriver(ds)), "VRT") == 0 &&
            nanIsNodata;
        for (std::size_t i = 0; i < buf.size(); ++i) {
            const double v = buf[i];
            if (std::isnan(v)) {
                if (!nanIsNodata && !warped) {
                    d.error("IMPORT_NAN", sourceName,
                            "row " + std::to_string(row0 + yOff + int(i / std::size_t(width))),
                            "source contains NaN values but NaN is not its nodata value");
                    return d;
                }
                out[i] = std::numeric_limits<float>::quiet_NaN();
            } else if (hasNodata && v == nodata) {
                out[i] = std::numeric_limits<float>::quiet_NaN();
            } else if (!std::isfinite(v)) {
                d.error("IMPORT_NAN", sourceName,
                        "row " + std::to_string(row0 + yOff + int(i / std::size_t(width))),
                        "source contains infinite values");
                return d;
            } else {
                out[i] = float(v * scale + offset);
            }
        }
        return d;
    };
}

RgbaRowSource rgbaRows(const PlacedSource& p, const std::string& sourceName) {
    GDALDatasetH ds = p.ds;
    const int xOff = p.xOff, yOff = p.yOff, width = p.window.width();
    return [=](int row0, int rows, std::uint8_t* out) -> Diagnostics {
        Diagnostics d;
        const int n = GDALGetRasterCount(ds);
        int alphaBand = 0;
        std::vector<int> colour;
        for (int i = 1; i <= n; ++i) {
            if (GDALGetRasterColorInterpretation(GDALGetRasterBand(ds, i)) == GCI_AlphaBand)
                alphaBand = i;
            else if (colour.size() < 3)
                colour.push_back(i);
        }
        if (colour.empty()) {
            d.error("IMPORT_READ", sourceName, "", "imagery has no colour band");
            return d;
        }
        const std::size_t count = std::size_t(width) * std::size_t(rows);
        std::vector<std::uint8_t> buf(count);
        auto read = [&](int band, int channel) -> bool {
            if (GDALRasterIO(GDALGetRasterBand(ds, band), GF_Read, xOff, yOff + row0, width, rows,
                             buf.data(), width, rows, GDT_Byte, 0, 0) != CE_None)
                return false;
            for (std::size_t i = 0; i < count; ++i) out[i * 4 + std::size_t(channel)] = buf[i];
            return true;
        };
        CPLErrorReset();
        bool ok = true;
        for (int c = 0; c < 3 && ok; ++c)
            ok = read(colour[colour.size() == 3 ? std::size_t(c) : 0], c);
        if (ok && alphaBand) ok = read(alphaBand, 3);
        if (!alphaBand)
            for (std::size_t i = 0; i < count; ++i) out[i * 4 + 3] = 255;
        if (!ok) d.error("IMPORT_READ", sourceName, "", gdalError("cannot read imagery rows"));
        return d;
    };
}

}  // namespace kiosk::import
