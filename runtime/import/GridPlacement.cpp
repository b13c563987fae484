// Placing a GDAL source on the store grid: planning a new store's grid from the source, and
// warping a source onto an existing grid (GdalRaster.h).
#include "runtime/import/Curvilinear.h"
#include "runtime/import/GdalRaster.h"
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

// A VRT copy of `src` we may re-georeference without touching the file.
GdalDataset vrtCopy(GDALDatasetH src) {
    GDALDriverH vrt = GDALGetDriverByName("VRT");
    return GdalDataset(GDALCreateCopy(vrt, "", src, FALSE, nullptr, nullptr, nullptr));
}

Result<GdalDataset> warpToVrt(GDALDatasetH src, const std::vector<std::string>& args,
                              const std::string& name) {
    CPLStringList argv;
    for (const auto& a : args) argv.AddString(a.c_str());
    GDALWarpAppOptions* o = GDALWarpAppOptionsNew(argv.List(), nullptr);
    int usageError = 0;
    GDALDatasetH in[1] = {src};
    CPLErrorReset();
    GDALDatasetH out = GDALWarp("", nullptr, 1, in, o, &usageError);
    GDALWarpAppOptionsFree(o);
    if (!out) {
        Diagnostics d;
        d.error("IMPORT_WARP", name, "", gdalError("cannot reproject the source"));
        return d;
    }
    return GdalDataset(out);
}

// GDAL's suggested output size of warping `ds` into `dstWkt` (what gdalwarp would create).
bool suggestedWarpSize(GDALDatasetH ds, const std::string& dstWkt, int& nx, int& ny,
                       const std::vector<std::string>& transformerOptions) {
    CPLStringList topts;
    topts.SetNameValue("DST_SRS", dstWkt.c_str());
    for (const auto& o : transformerOptions) topts.AddString(o.c_str());
    void* tr = GDALCreateGenImgProjTransformer2(ds, nullptr, topts.List());
    if (!tr) return false;
    double ogt[6], ext[4];
    const bool ok =
        GDALSuggestedWarpOutput2(ds, GDALGenImgProjTransform, tr, ogt, &nx, &ny, ext, 0) == CE_None;
    GDALDestroyGenImgProjTransformer(tr);
    return ok && nx > 0 && ny > 0;
}

std::string fmt(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

}  // namespace

Result<PlannedSource> planGrid(GdalDataset source, const PlaceOptions& options, int tileSize) {
    Diagnostics d;
    PlannedSource out;
    PlaceOptions opt = options;
    std::optional<StoreCrs> srcCrs;
    std::optional<Geolocation> geoloc;
    auto geo = georeference(std::move(source), opt, srcCrs, out.placed.chain, &geoloc);
    if (!geo) return geo.diagnostics;
    GDALDatasetH ds = *geo;
    const std::int64_t geolocBytes = geoloc ? geoloc->bytes : 0;

    StoreCrs target;
    bool warp = false;
    if (opt.toCrs) {
        auto c = crsFromUser(*opt.toCrs, "--to-crs");
        if (!c) return c.diagnostics;
        if (!srcCrs) {
            d.error("IMPORT_BAD_CRS", opt.sourceName, "--to-crs",
                    "the source has no CRS to reproject from")
                .hint = "name it with --assign-crs";
            return d;
        }
        target = *c;
        warp = !sameCrs(srcCrs->wkt, target.wkt);
    } else if (srcCrs && isGeographicCrs(srcCrs->wkt)) {
        target = autoTargetCrs(geoloc ? geoloc->extent : lonLatExtent(ds));
        warp = true;
    } else if (srcCrs) {
        target = *srcCrs;
    } else {
        target = localCrs();
    }
    if (geoloc) warp = true;  // a curvilinear grid has no geotransform: always resampled
    double gt[6];
    GDALGetGeoTransform(ds, gt);
    const bool square = gt[2] == 0 && gt[4] == 0 && gt[5] < 0 &&
                        std::fabs(std::fabs(gt[5]) - gt[1]) <= 1e-9 * gt[1];
    GDALDatasetH placed = ds;
    if (warp || !square) {
        std::vector<std::string> args = {
            "-of", "VRT", "-r", opt.nearest ? "near" : "bilinear", "-wo", "INIT_DEST=NO_DATA"};
        if (!opt.imagery)
            args.insert(args.end(), {"-ot", "Float32", "-dstnodata", "nan"});
        else
            args.insert(args.end(), {"-dstalpha"});
        // Pre-flight: the output size, before any VRT (or buffer) of that size exists.
        std::int64_t outW = 0, outH = 0;
        if (warp) {
            // GDAL suggests a square pixel in the *target* CRS (same pixel count along the
            // diagonal); a source pixel size in degrees must never be used with a metre CRS.
            args.insert(args.end(), {"-t_srs", target.wkt});
            int nx = 0, ny = 0;
            if (geoloc) {
                const auto to = geolocationWarpArgs(*geoloc);
                args.insert(args.end(), to.begin(), to.end());
            }
            if (!suggestedWarpSize(
                    ds, target.wkt, nx, ny,
                    geoloc ? geolocationTransformerOptions(*geoloc) : std::vector<std::string>())) {
                d.error("IMPORT_WARP", opt.sourceName, "",
                        gdalError("cannot transform the source into " + target.name));
                return d;
            }
            outW = nx, outH = ny;
        } else {
            const double p = std::min(std::fabs(gt[1]), std::fabs(gt[5]));
            args.insert(args.end(), {"-tr", fmt(p), fmt(p)});
            outW = std::int64_t(std::ceil(std::fabs(gt[1]) * GDALGetRasterXSize(ds) / p));
            outH = std::int64_t(std::ceil(std::fabs(gt[5]) * GDALGetRasterYSize(ds) / p));
        }
        d = checkImportBudget(outW, outH, tileSize, geolocBytes, opt.memoryBudget, opt.sourceName);
        if (d.hasErrors()) return d;
        auto w = warpToVrt(ds, args, opt.sourceName);
        if (!w) return w.diagnostics;
        placed = out.placed.chain.add(std::move(*w));
        GDALGetGeoTransform(placed, gt);
    }
    const int width = GDALGetRasterXSize(placed), height = GDALGetRasterYSize(placed);
    const double p = gt[1];
    if (!(p > 0) || width < 1 || height < 1) {
        d.error("IMPORT_NO_GEOREF", opt.sourceName, "", "source has an invalid geotransform");
        return d;
    }
    d = checkImportBudget(width, height, tileSize, geolocBytes, opt.memoryBudget, opt.sourceName);
    if (d.hasErrors()) return d;
    int levels = 1;
    while (std::int64_t(tileSize) << (levels - 1) < std::max(width, height)) ++levels;
    io::TileGrid& g = out.grid;
    g.srsId = target.srsId;
    g.crsName = target.name;
    g.crsWkt = target.wkt;
    const double size = p * double(std::int64_t(tileSize) << (levels - 1));
    g.minX = gt[0];
    g.maxY = gt[3];
    g.maxX = g.minX + size;
    g.minY = g.maxY - size;
    g.setPyramid(levels, tileSize, tileSize, p);
    out.placed.ds = placed;
    out.placed.window = {0, 0, width, height};
    return out;
}

Result<PlacedSource> placeOnGrid(GdalDataset source, const io::TileGrid& grid,
                                 const PlaceOptions& options) {
    Diagnostics d;
    std::optional<StoreCrs> srcCrs;
    PlaceOptions opt = options;
    PlacedSource ps;
    std::optional<Geolocation> geoloc;
    auto geo = georeference(std::move(source), opt, srcCrs, ps.chain, &geoloc);
    if (!geo) return geo.diagnostics;
    GDALDatasetH src = *geo;
    const std::vector<std::string> geolocOptions =
        geoloc ? geolocationTransformerOptions(*geoloc) : std::vector<std::string>();
    if (opt.toCrs) {
        auto c = crsFromUser(*opt.toCrs, "--to-crs");
        if (!c) return c.diagnostics;
        if (!sameCrs(c->wkt, grid.crsWkt)) {
            d.error("IMPORT_CRS_MISMATCH", opt.sourceName, "--to-crs",
                    "the store's CRS is " + grid.crsName + "; --to-crs applies to a new store")
                .hint = "drop --to-crs: the source is warped to the store's CRS";
            return d;
        }
    }
    const bool noCrs = !srcCrs;
    if (noCrs) {
        // A CRS-less source on a store: its coordinates are taken to be the store's.
        src = ps.chain.add(vrtCopy(src));
        if (!src) {
            d.error("IMPORT_UNREADABLE", opt.sourceName, "", gdalError("cannot wrap the source"));
            return d;
        }
        GDALSetProjection(src, grid.crsWkt.c_str());
        srcCrs = crsOfDataset(src);
    }
    const io::TileMatrix& finest = grid.levels.back();
    const double p = finest.pixelXSize;
    const std::int64_t full = std::int64_t(finest.tileWidth) * finest.matrixWidth;
    double gt[6];
    GDALGetGeoTransform(src, gt);
    const int sw = GDALGetRasterXSize(src), sh = GDALGetRasterYSize(src);
    // A curvilinear source has no geotransform: even in the store's CRS it is warped.
    const bool same = !geoloc && (!srcCrs || sameCrs(srcCrs->wkt, grid.crsWkt));
    if (noCrs)
        ps.warnings.push_back("source has no CRS; assuming the store's (" + grid.crsName + ")");

    double minX, minY, maxX, maxY;
    if (same) {
        minX = gt[0];
        maxX = gt[0] + gt[1] * sw;
        maxY = gt[3];
        minY = gt[3] + gt[5] * sh;
        if (minY > maxY) std::swap(minY, maxY);
    } else {
        CPLStringList topts;
        topts.SetNameValue("DST_SRS", grid.crsWkt.c_str());
        for (const auto& o : geolocOptions) topts.AddString(o.c_str());
        void* tr = GDALCreateGenImgProjTransformer2(src, nullptr, topts.List());
        double ogt[6], ext[4];
        int nx = 0, ny = 0;
        if (!tr || GDALSuggestedWarpOutput2(src, GDALGenImgProjTransform, tr, ogt, &nx, &ny, ext,
                                            0) != CE_None) {
            if (tr) GDALDestroyGenImgProjTransformer(tr);
            d.error(
                "IMPORT_CRS_MISMATCH", opt.sourceName, "",
                gdalError("cannot transform the source into the store CRS (" + grid.crsName + ")"));
            return d;
        }
        GDALDestroyGenImgProjTransformer(tr);
        minX = ext[0], minY = ext[1], maxX = ext[2], maxY = ext[3];
    }
    GridWindow w;
    w.x0 = int(std::clamp<double>(std::floor((minX - grid.minX) / p + 1e-6), 0, double(full)));
    w.x1 = int(std::clamp<double>(std::ceil((maxX - grid.minX) / p - 1e-6), 0, double(full)));
    w.y0 = int(std::clamp<double>(std::floor((grid.maxY - maxY) / p + 1e-6), 0, double(full)));
    w.y1 = int(std::clamp<double>(std::ceil((grid.maxY - minY) / p - 1e-6), 0, double(full)));
    if (w.empty()) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "source extent (%.1f %.1f, %.1f %.1f) does not overlap the store extent "
                      "(%.1f %.1f, %.1f %.1f)",
                      minX, minY, maxX, maxY, grid.minX, grid.minY, grid.maxX, grid.maxY);
        d.error("IMPORT_EXTENT_MISMATCH", opt.sourceName, "", buf);
        return d;
    }
    ps.window = w;
    d = checkImportBudget(w.width(), w.height(), finest.tileWidth, geoloc ? geoloc->bytes : 0,
                          opt.memoryBudget, opt.sourceName);
    if (d.hasErrors()) return d;
    const double ox = (gt[0] - grid.minX) / p, oy = (grid.maxY - gt[3]) / p;
    const bool aligned = same && gt[2] == 0 && gt[4] == 0 && std::fabs(gt[1] - p) <= 1e-9 * p &&
                         std::fabs(gt[5] + p) <= 1e-9 * p &&
                         std::fabs(ox - std::round(ox)) < 1e-6 &&
                         std::fabs(oy - std::round(oy)) < 1e-6 && !opt.imagery;
    if (aligned) {
        ps.ds = src;
        ps.xOff = w.x0 - int(std::round(ox));
        ps.yOff = w.y0 - int(std::round(oy));
        return ps;
    }
    std::vector<std::string> args = {"-of",
                                     "VRT",
                                     "-r",
                                     opt.nearest ? "near" : "bilinear",
                                     "-wo",
                                     "INIT_DEST=NO_DATA",
                                     "-t_srs",
                                     grid.crsWkt,
                                     "-te",
                                     fmt(grid.minX + w.x0 * p),
                                     fmt(grid.maxY - w.y1 * p),
                                     fmt(grid.minX + w.x1 * p),
                                     fmt(grid.maxY - w.y0 * p),
                                     "-ts",
                                     std::to_string(w.width()),
                                     std::to_string(w.height())};
    if (opt.imagery)
        args.insert(args.end(), {"-ot", "Byte", "-dstalpha"});
    else
        args.insert(args.end(), {"-ot", "Float32", "-dstnodata", "nan"});
    for (const auto& o : geolocOptions) args.insert(args.end(), {"-to", o});
    auto warped = warpToVrt(src, args, opt.sourceName);
    if (!warped) return warped.diagnostics;
    ps.ds = ps.chain.add(std::move(*warped));
    ps.xOff = ps.yOff = 0;
    return ps;
}

}  // namespace kiosk::import
