#include "runtime/import/GeoTarget.h"

#include "runtime/import/Curvilinear.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal_vrt.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kiosk::import {

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// CF 1.x, section 4.1/4.2: the accepted spellings of longitude and latitude units.
bool isLonUnit(const std::string& u) {
    const std::string l = lower(u);
    return l == "degrees_east" || l == "degree_east" || l == "degree_e" || l == "degrees_e" ||
           l == "degreee" || l == "degreese";
}
bool isLatUnit(const std::string& u) {
    const std::string l = lower(u);
    return l == "degrees_north" || l == "degree_north" || l == "degree_n" || l == "degrees_n" ||
           l == "degreen" || l == "degreesn";
}

}  // namespace

bool hasCfLonLatAxes(GDALDatasetH ds) {
    bool lon = false, lat = false;
    char** md = GDALGetMetadata(ds, nullptr);
    for (int i = 0; md && md[i]; ++i) {
        const std::string item = md[i];
        const auto eq = item.find('=');
        if (eq == std::string::npos) continue;
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        const auto hash = key.find('#');
        if (hash == std::string::npos || hash == 0) continue;  // NC_GLOBAL#... has no '#' at 0
        const std::string att = key.substr(hash + 1);
        if (att == "units") {
            lon = lon || isLonUnit(value);
            lat = lat || isLatUnit(value);
        } else if (att == "standard_name") {
            lon = lon || lower(value) == "longitude";
            lat = lat || lower(value) == "latitude";
        }
    }
    return lon && lat;
}

StoreCrs wgs84() {
    auto c = crsFromUser("EPSG:4326");
    return c ? *c : localCrs();
}

double LonLatExtent::centreLon() const {
    double c = std::fmod((west + east) / 2.0 + 180.0, 360.0);
    if (c < 0) c += 360.0;
    return c - 180.0;
}

LonLatExtent lonLatExtent(GDALDatasetH ds) {
    double gt[6];
    GDALGetGeoTransform(ds, gt);
    const double w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
    LonLatExtent e;
    e.west = std::min(gt[0], gt[0] + gt[1] * w);
    e.east = std::max(gt[0], gt[0] + gt[1] * w);
    e.north = std::max(gt[3], gt[3] + gt[5] * h);
    e.south = std::min(gt[3], gt[3] + gt[5] * h);
    return e;
}

int globeColumns(const double gt[6], int width) {
    if (!(gt[1] > 0) || gt[2] != 0 || gt[4] != 0) return 0;
    const double perGlobe = 360.0 / gt[1];
    const long n = std::lround(perGlobe);
    // Coordinates stored as float32 put the step a little off 360 / n.
    if (n < 2 || std::fabs(perGlobe - double(n)) > 0.01) return 0;
    if (width < n || width > n + kMaxWrapColumns) return 0;
    // Degrees, not metres that happen to divide 360: the grid starts within one turn of 0.
    if (gt[0] < -360.0 - 1e-9 || gt[0] >= 360.0) return 0;
    return int(n);
}

namespace {

// A VRT of the first `columns` columns of `ds` starting at column `k` and wrapping to column 0
// after `columns` (k = 0: a plain window), placed at geotransform `ngt`.
Result<GDALDatasetH> wrappedColumns(GDALDatasetH ds, DatasetChain& chain, int k, int columns,
                                    const double ngt[6], const std::string& sourceName) {
    const int height = GDALGetRasterYSize(ds);
    VRTDatasetH vrt = VRTCreate(columns, height);
    GDALDatasetH out = chain.add(GdalDataset(vrt));
    GDALSetGeoTransform(out, const_cast<double*>(ngt));
    if (const char* wkt = GDALGetProjectionRef(ds)) GDALSetProjection(out, wkt);
    GDALSetMetadata(out, GDALGetMetadata(ds, nullptr), nullptr);
    for (int b = 1; b <= GDALGetRasterCount(ds); ++b) {
        GDALRasterBandH src = GDALGetRasterBand(ds, b);
        VRTAddBand(vrt, GDALGetRasterDataType(src), nullptr);
        GDALRasterBandH dst = GDALGetRasterBand(out, b);
        int has = 0;
        const double nodata = GDALGetRasterNoDataValue(src, &has);
        if (has) GDALSetRasterNoDataValue(dst, nodata);
        GDALSetRasterScale(dst, GDALGetRasterScale(src, nullptr));
        GDALSetRasterOffset(dst, GDALGetRasterOffset(src, nullptr));
        GDALSetRasterUnitType(dst, GDALGetRasterUnitType(src));
        GDALSetRasterColorInterpretation(dst, GDALGetRasterColorInterpretation(src));
        GDALSetMetadata(dst, GDALGetMetadata(src, nullptr), nullptr);
        const double nd = has ? nodata : -1234567.0;  // VRT's "no nodata" marker
        const bool ok =
            VRTAddSimpleSource(VRTSourcedRasterBandH(dst), src, k, 0, columns - k, height, 0, 0,
                               columns - k, height, "near", nd) == CE_None &&
            (k == 0 || VRTAddSimpleSource(VRTSourcedRasterBandH(dst), src, 0, 0, k, height,
                                          columns - k, 0, k, height, "near", nd) == CE_None);
        if (!ok) {
            Diagnostics d;
            d.error("IMPORT_UNREADABLE", sourceName, "",
                    gdalError("cannot roll the longitudes to -180..180"));
            return d;
        }
    }
    return out;
}

}  // namespace

Result<GDALDatasetH> normaliseLongitudes(GDALDatasetH ds, DatasetChain& chain,
                                         const std::string& sourceName) {
    double gt[6];
    if (GDALGetGeoTransform(ds, gt) != CE_None || gt[2] != 0 || gt[4] != 0 || !(gt[1] > 0))
        return ds;
    const int width = GDALGetRasterXSize(ds);
    if (const int globe = globeColumns(gt, width)) {
        // The whole globe from any start meridian: the start moved into -180..180 by whole
        // turns, the columns past 360 degrees dropped, and the columns whose centre is at or
        // past 180 moved to the west end, so the grid runs from (about) -180 to 180.
        const double west = gt[0] - 360.0 * std::floor((gt[0] + 180.0) / 360.0);
        int k = 0;
        if (west + globe * gt[1] > 180.0 + 1e-9)
            k = std::clamp(int(std::ceil((180.0 - west) / gt[1] - 0.5)), 0, globe) % globe;
        if (k == 0 && globe == width && west == gt[0]) return ds;
        double ngt[6] = {west + k * gt[1] - (k ? 360.0 : 0.0), gt[1], 0, gt[3], 0, gt[5]};
        return wrappedColumns(ds, chain, k, globe, ngt, sourceName);
    }
    const LonLatExtent e = lonLatExtent(ds);
    if (e.east <= 180.0 + 1e-9) return ds;
    Diagnostics d;
    if (e.west >= 180.0 - 1e-9) {
        // Wholly east of the dateline in 0..360 terms: the same grid 360 degrees west.
        GDALDatasetH copy = chain.add(GdalDataset(
            GDALCreateCopy(GDALGetDriverByName("VRT"), "", ds, FALSE, nullptr, nullptr, nullptr)));
        if (!copy) {
            d.error("IMPORT_UNREADABLE", sourceName, "", "cannot wrap the source");
            return d;
        }
        gt[0] -= 360.0;
        GDALSetGeoTransform(copy, gt);
        return copy;
    }
    if (e.lonSpan() < 360.0 - gt[1] * 0.5) return ds;  // regional across 180: keep continuous
    // Whole globe on 0..360: columns whose centre is at or past 180 move to the west end.
    int k = int(std::ceil((180.0 - e.west) / gt[1] - 0.5));
    k = std::clamp(k, 0, width);
    if (k == 0 || k == width) return ds;
    double ngt[6] = {e.west + k * gt[1] - 360.0, gt[1], 0, gt[3], 0, gt[5]};
    return wrappedColumns(ds, chain, k, width, ngt, sourceName);
}

StoreCrs autoTargetCrs(const LonLatExtent& e) {
    const bool regional = e.lonSpan() <= kRegionalSpanDeg && e.latSpan() <= kRegionalSpanDeg &&
                          e.south >= -80.0 && e.north <= 84.0;
    const double lon = e.centreLon();
    if (regional) return utmCrsFor(lon, (e.south + e.north) / 2.0);
    // Whole degrees keep the definition readable (and EPSG:4087 for Greenwich-centred data).
    const double lon0 = std::round(lon);
    if (lon0 == 0.0 || e.lonSpan() >= 359.0) {
        if (auto c = crsFromUser("EPSG:4087")) return *c;
    }
    char def[160];
    std::snprintf(def, sizeof def,
                  "+proj=eqc +lat_ts=0 +lat_0=0 +lon_0=%g +x_0=0 +y_0=0 +datum=WGS84 +units=m "
                  "+no_defs",
                  lon0);
    auto c = crsFromUser(def);
    if (!c) return localCrs();
    c->name = "WGS 84 / equidistant cylindrical, lon_0 " + std::to_string(int(lon0));
    return *c;
}

std::int64_t estimateImportBytes(std::int64_t width, int tileSize, std::int64_t extraBytes) {
    const std::int64_t gdalCache = std::int64_t(96) << 20;  // initGdal's block cache
    return width * (std::int64_t(tileSize) + 1) * 24 + gdalCache + extraBytes;
}

Diagnostics checkImportBudget(std::int64_t width, std::int64_t height, int tileSize,
                              std::int64_t extraBytes, std::int64_t budget,
                              const std::string& sourceName) {
    Diagnostics d;
    const std::int64_t need = estimateImportBytes(width, tileSize, extraBytes);
    if (need <= budget) return d;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "import needs about %lld MiB for a %lld x %lld pixel grid, above the %lld MiB "
                  "budget",
                  static_cast<long long>(need >> 20), static_cast<long long>(width),
                  static_cast<long long>(height), static_cast<long long>(budget >> 20));
    d.error("IMPORT_TOO_LARGE", sourceName, "", buf).hint =
        "check --pixel-size / the source's pixel size, or raise --max-memory MB";
    return d;
}

}  // namespace kiosk::import

namespace kiosk::import {

namespace {

GdalDataset vrtOf(GDALDatasetH src) {
    return GdalDataset(
        GDALCreateCopy(GDALGetDriverByName("VRT"), "", src, FALSE, nullptr, nullptr, nullptr));
}

}  // namespace

Result<GDALDatasetH> georeference(GdalDataset source, PlaceOptions& opt,
                                  std::optional<StoreCrs>& crs, DatasetChain& chain,
                                  std::optional<Geolocation>* geolocation) {
    Diagnostics d;
    double gt[6];
    GDALDatasetH src = chain.add(std::move(source));
    const bool hasGt = GDALGetGeoTransform(src, gt) == CE_None &&
                       !(gt[0] == 0 && gt[1] == 1 && gt[3] == 0 && gt[5] == 1);
    if (!hasGt) {
        // 2-D longitude/latitude arrays locate every pixel: warped through them, never assigned.
        auto g = geolocationOf(src, opt.memoryBudget, opt.sourceName);
        if (!g) return g.diagnostics;
        if (*g) {
            if (opt.assignCrs) {
                d.error("IMPORT_BAD_CRS", opt.sourceName, "--assign-crs",
                        "the source is located by geolocation arrays in " + (*g)->crs.name +
                            "; --assign-crs does not apply to it")
                    .hint = "drop --assign-crs (--to-crs chooses the store's CRS)";
                return d;
            }
            if (opt.crs && !opt.toCrs) opt.toCrs = opt.crs;
            opt.crs.reset();
            crs = (*g)->crs;
            if (geolocation) *geolocation = **g;
            return src;
        }
    }
    crs = crsOfDataset(src);
    const bool cfLonLat = !crs && hasGt && hasCfLonLatAxes(src);
    // The old --crs meant "assign" for CRS-less input and "warp to" otherwise.
    if (opt.crs) {
        if (crs || cfLonLat) {
            if (!opt.toCrs) opt.toCrs = opt.crs;
        } else if (!opt.assignCrs) {
            opt.assignCrs = opt.crs;
        }
        opt.crs.reset();
    }
    std::optional<StoreCrs> assign;
    if (opt.assignCrs) {
        auto c = crsFromUser(*opt.assignCrs, "--assign-crs");
        if (!c) return c.diagnostics;
        assign = *c;
    } else if (cfLonLat) {
        assign = wgs84();  // CF: bare lon/lat axes are geographic; WGS 84 is the usual datum
    }
    if (hasGt && assign) {
        const bool geographic = isGeographicCrs(assign->wkt);
        if (cfLonLat && !geographic) {
            d.error(
                 "IMPORT_BAD_CRS", opt.sourceName, "--assign-crs",
                 "the source's axes are longitude/latitude (CF degrees_east/degrees_north) but " +
                     assign->name + " is projected")
                .hint = "use --to-crs to reproject; --assign-crs names the source's own CRS";
            return d;
        }
        const LonLatExtent e = lonLatExtent(src);
        // A whole-globe grid may start at any meridian and repeat columns past 360 degrees
        // (normaliseLongitudes drops them); its longitudes need no range.
        const bool globe = globeColumns(gt, GDALGetRasterXSize(src)) > 0;
        if (geographic && ((!globe && (e.west < -180.0 - 1e-6 || e.east > 360.0 + 1e-6)) ||
                           e.south < -90.0 - 1e-6 || e.north > 90.0 + 1e-6)) {
            char buf[200];
            std::snprintf(buf, sizeof buf,
                          "coordinates (%.6g %.6g, %.6g %.6g) are not longitude/latitude, so "
                          "they cannot be in %s",
                          e.west, e.south, e.east, e.north, assign->name.c_str());
            d.error("IMPORT_BAD_CRS", opt.sourceName, "--assign-crs", buf);
            return d;
        }
    }
    GDALDatasetH ds = src;
    if (!hasGt || assign) {
        if (!hasGt && !opt.pixelSize) {
            d.error("IMPORT_NO_GEOREF", opt.sourceName, "",
                    "source has no georeferencing (give --pixel-size M, and --assign-crs if "
                    "known)");
            return d;
        }
        ds = chain.add(vrtOf(src));
        if (!ds) {
            d.error("IMPORT_UNREADABLE", opt.sourceName, "", gdalError("cannot wrap the source"));
            return d;
        }
        if (!hasGt) {
            const double p = *opt.pixelSize;
            const double h = GDALGetRasterYSize(ds);
            double g[6] = {0, p, 0, h * p, 0, -p};
            GDALSetGeoTransform(ds, g);
        }
        if (assign) {
            GDALSetProjection(ds, assign->wkt.c_str());
            crs = crsOfDataset(ds);
            if (crs) crs->srsId = assign->srsId;
        }
    }
    if (crs && isGeographicCrs(crs->wkt)) return normaliseLongitudes(ds, chain, opt.sourceName);
    return ds;
}

}  // namespace kiosk::import
