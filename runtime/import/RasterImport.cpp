// `import elevation` and `import imagery` of GDAL rasters.
#include "runtime/import/GeoTarget.h"
#include "runtime/import/ImageryResolution.h"
#include "runtime/import/ImportSteps.h"
#include "runtime/import/TempStore.h"

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdal_utils.h>

#include <cctype>
#include <cmath>
#include <filesystem>

namespace kiosk::import {

namespace fs = std::filesystem;

namespace {

// Vertical units: what the source declares against what the user declares.
Result<double> unitFactor(GDALDatasetH ds, int band, const ImportOptions& o,
                          const std::string& src) {
    Diagnostics d;
    const std::string stated = GDALGetRasterUnitType(GDALGetRasterBand(ds, band));
    std::string declared = stated;
    for (char& c : declared) c = char(std::tolower(static_cast<unsigned char>(c)));
    auto isFeet = [](const std::string& u) {
        return u == "ft" || u == "foot" || u == "feet" || u == "us survey foot" ||
               u == "us_survey_foot" || u == "ftus";
    };
    auto isMetre = [](const std::string& u) {
        return u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters";
    };
    const bool srcFeet = isFeet(declared), srcMetre = isMetre(declared);
    if (o.units && *o.units != "m" && *o.units != "ft") {
        d.error("IMPORT_USAGE", src, "--units",
                "elevation units must be m or ft, not '" + *o.units + "'");
        return d;
    }
    if (o.units && ((*o.units == "m" && srcFeet) || (*o.units == "ft" && srcMetre))) {
        d.error("IMPORT_UNITS_MISMATCH", src, "",
                "source declares its values in '" + declared + "' but --units " + *o.units +
                    " was given");
        return d;
    }
    const double usFoot = 1200.0 / 3937.0;
    if (srcFeet) return declared.find("us") != std::string::npos ? usFoot : 0.3048;
    // A unit that is no length (a temperature grid given as a DEM?) is read as metres, but said.
    if (!o.units && !srcMetre && !declared.empty())
        d.warning("IMPORT_UNITS_ASSUMED", src, "",
                  "source states its values are in '" + stated +
                      "', not a length; read as metres (--units m or ft says which)");
    if (o.units && *o.units == "ft") return Result<double>(0.3048, d);
    return Result<double>(1.0, d);
}

// Elevation reads one band: a colour (or any multi-band) raster needs --band, never band 1
// silently.
Result<int> elevationBand(GDALDatasetH ds, const ImportOptions& o, const std::string& source) {
    Diagnostics d;
    const int n = GDALGetRasterCount(ds);
    if (o.band) {
        if (*o.band < 1 || *o.band > n) {
            d.error("IMPORT_USAGE", source, "--band",
                    "band " + std::to_string(*o.band) + " does not exist (the source has " +
                        std::to_string(n) + ")");
            return d;
        }
        return *o.band;
    }
    if (n == 1) return 1;
    std::string kinds;
    for (int b = 1; b <= n && b <= 4; ++b) {
        if (!kinds.empty()) kinds += ", ";
        kinds += GDALGetColorInterpretationName(
            GDALGetRasterColorInterpretation(GDALGetRasterBand(ds, b)));
    }
    const bool colour = GDALGetRasterColorInterpretation(GDALGetRasterBand(ds, 1)) == GCI_RedBand;
    d.error("IMPORT_MULTIBAND", source, "",
            std::string(colour ? "a colour raster" : "a multi-band raster") + " (" +
                std::to_string(n) + " bands: " + kinds + (n > 4 ? ", ..." : "") +
                ") is not an elevation model")
        .hint = colour ? "import it with 'import imagery', or pick a band with --band N"
                       : "pick the elevation band with --band N";
    return d;
}

}  // namespace

Diagnostics importElevationSource(const std::string& source, const ImportOptions& o) {
    initGdal();
    if (lowerExt(source) == ".sww") return importSwwElevation(source, o);
    auto src = openRaster(source);
    if (!src) return src.diagnostics;
    auto bandNo = elevationBand(raw(*src), o, source);
    if (!bandNo) return bandNo.diagnostics;
    const int band = *bandNo;
    if (o.fillVoids) {
        // The copy holds every band of the raster in memory: part of the pre-flight estimate.
        const std::int64_t w = GDALGetRasterXSize(raw(*src)), h = GDALGetRasterYSize(raw(*src));
        const std::int64_t held =
            w * h * GDALGetRasterCount(raw(*src)) *
            GDALGetDataTypeSizeBytes(GDALGetRasterDataType(GDALGetRasterBand(raw(*src), band)));
        Diagnostics b = checkImportBudget(w, h, o.tileSize, held, o.memoryBudget, source);
        if (b.hasErrors()) return b;
        // Voids read as holes in the terrain; a kiosk should show a plausible surface instead.
        GDALDriverH mem = GDALGetDriverByName("MEM");
        GDALDatasetH copy =
            mem ? GDALCreateCopy(mem, "", raw(*src), FALSE, nullptr, nullptr, nullptr) : nullptr;
        if (!copy || GDALFillNodata(GDALGetRasterBand(copy, band), nullptr, 100.0, 0, 0, nullptr,
                                    nullptr, nullptr) != CE_None) {
            if (copy) GDALClose(copy);
            Diagnostics d;
            d.error("IMPORT_FILL_VOIDS", source, "", gdalError("cannot fill voids"));
            return d;
        }
        *src = GdalDataset(copy);
    }
    auto factor = unitFactor(raw(*src), band, o, source);
    if (!factor) return factor.diagnostics;
    const double f = *factor * o.zScale;
    std::optional<double> nodata;
    int hasNodata = 0;
    const double nd = GDALGetRasterNoDataValue(GDALGetRasterBand(raw(*src), band), &hasNodata);
    if (hasNodata) nodata = nd;
    auto range = bandRange(raw(*src), band);
    if (!range) {
        Diagnostics d;
        d.error("IMPORT_ALL_NODATA", source, "", "source holds no valid value (all nodata)");
        return d;
    }
    range->first *= std::fabs(f);
    range->second *= std::fabs(f);
    Diagnostics warnings = factor.diagnostics;
    Progress progress(o.quiet);
    Diagnostics d = withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        PlaceOptions po = placeOptions(o, source);
        auto ps = placeSource(w, std::move(*src), po, o.tileSize, warnings);
        if (!ps) return ps.diagnostics;
        ScalarImport si;
        si.table = o.name.empty() ? "elevation" : o.name;
        si.units = "m";
        si.nodata = nodata;
        auto r = importScalarLayer(w, *ps, scalarRows(*ps, band, f, source), range, si, o, source,
                                   progress);
        return r.diagnostics;
    });
    warnings.append(d);
    return warnings;
}

Diagnostics importImagerySource(const std::string& source, const ImportOptions& o) {
    initGdal();
    Diagnostics d;
    if (o.name.empty()) {
        d.error("IMPORT_USAGE", source, "--name", "imagery needs --name");
        return d;
    }
    auto src = openRaster(source);
    if (!src) return src.diagnostics;
    GdalDataset paletteSource;
    // Palette images become RGBA before warping (the warper would blend palette indices).
    GDALRasterBandH b1 = GDALGetRasterBand(raw(*src), 1);
    if (GDALGetRasterColorTable(b1)) {
        CPLStringList argv;
        argv.AddString("-of");
        argv.AddString("VRT");
        argv.AddString("-expand");
        argv.AddString("rgba");
        GDALTranslateOptions* to = GDALTranslateOptionsNew(argv.List(), nullptr);
        GDALDatasetH ex = GDALTranslate("", raw(*src), to, nullptr);
        GDALTranslateOptionsFree(to);
        if (!ex) {
            d.error("IMPORT_UNREADABLE", source, "", gdalError("cannot expand the palette"));
            return d;
        }
        // The expanded VRT reads from the original, which must outlive it.
        paletteSource = std::move(*src);
        *src = GdalDataset(ex);
    }
    Diagnostics warnings;
    Progress progress(o.quiet);
    d = withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        Diagnostics e;
        if (!w.grid()) {
            e.error("IMPORT_NO_GRID", o.store.string(), "",
                    "store has no elevation yet: import elevation first (imagery is placed on the "
                    "store's grid)");
            return e;
        }
        PlaceOptions po = placeOptions(o, source);
        po.imagery = true;
        // Its own resolution: finer imagery gets levels below the grid's finest.
        std::optional<std::string> assignWkt;
        if (const auto& a = o.assignCrs ? o.assignCrs : o.crs)
            if (auto c = crsFromUser(*a)) assignWkt = c->wkt;
        const int extra =
            imageryExtraLevels(raw(*src), *w.grid(), io::StoreWriter::kMaxExtraImageryLevels,
                               o.memoryBudget, assignWkt);
        const io::TileGrid grid = refinedGrid(*w.grid(), extra);
        auto ps = placeSource(w, std::move(*src), po, o.tileSize, warnings, &grid);
        if (!ps) return ps.diagnostics;
        e.append(w.createImageryLayer(
            o.name, "imported from " + fs::path(source).filename().string(), extra));
        if (e.hasErrors()) return e;
        PyramidOptions opt;
        opt.table = o.name;
        opt.threads = o.threads;
        opt.jpeg = o.jpeg;
        opt.progress = &progress;
        opt.failAfterTiles = o.failAfterTiles;
        opt.sourceName = source;
        progress.begin(o.name, estimateTiles(grid, ps->window));
        auto r = buildImageryPyramid(w, grid, ps->window, rgbaRows(*ps, source), opt);
        if (!r) return r.diagnostics;
        progress.finish();
        double x0, y0, x1, y1;
        windowExtent(grid, ps->window, x0, y0, x1, y1);
        e.append(r.diagnostics);
        e.append(w.finishLayer(o.name, 0, 255, x0, y0, x1, y1));
        return e;
    });
    warnings.append(d);
    return warnings;
}

}  // namespace kiosk::import
