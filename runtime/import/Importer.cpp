#include "runtime/import/Importer.h"

#include "runtime/core/Progress.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/CfTime.h"
#include "runtime/import/GdalRaster.h"
#include "runtime/import/GeoTarget.h"
#include "runtime/import/ImageryResolution.h"
#include "runtime/import/Pyramid.h"
#include "runtime/import/SourceUnits.h"
#include "runtime/import/SwwMesh.h"
#include "runtime/import/TempStore.h"
#include "runtime/import/TileMeshes.h"
#include "runtime/io/StoreWriter.h"

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdal_utils.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

namespace kiosk::import {

namespace fs = std::filesystem;

namespace {

std::string lowerExt(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

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

void windowExtent(const io::TileGrid& g, const GridWindow& w, double& x0, double& y0, double& x1,
                  double& y1) {
    const double p = g.levels.back().pixelXSize;
    x0 = g.minX + w.x0 * p;
    x1 = g.minX + w.x1 * p;
    y1 = g.maxY - w.y0 * p;
    y0 = g.maxY - w.y1 * p;
}

// Place a GDAL source on the store grid (or `onGrid`, a refinement of it), defining the grid
// first for a new store.
Result<PlacedSource> placeSource(io::StoreWriter& w, GdalDataset src, const PlaceOptions& po,
                                 int tileSize, Diagnostics& warnings,
                                 const io::TileGrid* onGrid = nullptr) {
    if (!w.grid()) {
        auto planned = planGrid(std::move(src), po, tileSize);
        if (!planned) return planned.diagnostics;
        Diagnostics d = w.defineGrid(planned->grid);
        if (d.hasErrors()) return d;
        if (!GDALGetSpatialRef(planned->placed.ds))
            warnings.warning("IMPORT_LOCAL_CRS", po.sourceName, "",
                             "source has no CRS; the store uses a local metric CRS "
                             "(give --assign-crs EPSG:N if it is known)");
        return std::move(planned->placed);
    }
    auto ps = placeOnGrid(std::move(src), onGrid ? *onGrid : *w.grid(), po);
    // A store on the local CRS holds only CRS-less data: nothing to warn about.
    if (ps && w.grid()->srsId != localCrs().srsId)
        for (const auto& m : ps->warnings)
            warnings.warning("IMPORT_ASSUMED_CRS", po.sourceName, "", m);
    return ps;
}

PlaceOptions placeOptions(const ImportOptions& o, const std::string& source) {
    PlaceOptions po;
    po.crs = o.crs;
    po.assignCrs = o.assignCrs;
    po.toCrs = o.toCrs;
    po.pixelSize = o.pixelSize;
    po.memoryBudget = o.memoryBudget;
    po.sourceName = source;
    return po;
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

struct ScalarImport {
    std::string table;
    io::LayerKind kind = io::LayerKind::Elevation;
    std::string units;
    bool categorical = false;
    double minStep = 1.0 / 256.0;
    std::optional<double> nodata;
};

Result<PyramidResult> importScalarLayer(io::StoreWriter& w, const PlacedSource& ps,
                                        const ScalarRowSource& rows,
                                        std::optional<std::pair<double, double>> range,
                                        const ScalarImport& si, const ImportOptions& o,
                                        const std::string& src, Progress& progress) {
    const double scale =
        si.categorical ? 1.0 : chooseScale(range ? range->second - range->first : 0.0, si.minStep);
    io::ScalarLayerSpec spec;
    spec.table = si.table;
    spec.kind = si.kind;
    spec.units = si.units;
    spec.scale = scale;
    spec.nodata = si.nodata;
    spec.description = "imported from " + fs::path(src).filename().string();
    Diagnostics d = w.createScalarLayer(spec);
    if (d.hasErrors()) return d;
    PyramidOptions po;
    po.table = si.table;
    po.scale = scale;
    po.categorical = si.categorical;
    po.threads = o.threads;
    po.progress = &progress;
    po.failAfterTiles = o.failAfterTiles;
    po.sourceName = src;
    progress.begin(si.table, estimateTiles(*w.grid(), ps.window));
    auto res = buildScalarPyramid(w, *w.grid(), ps.window, rows, po);
    if (!res) return res;
    progress.finish();
    double x0, y0, x1, y1;
    windowExtent(*w.grid(), ps.window, x0, y0, x1, y1);
    d.append(w.finishLayer(si.table, res->minValue, res->maxValue, x0, y0, x1, y1));
    if (d.hasErrors()) return d;
    if (si.kind == io::LayerKind::Elevation) {  // the loader decodes these instead of meshing
        auto meshes = storeTileMeshes(w, si.table, scale, o.threads, progress);
        if (!meshes) return meshes.diagnostics;
        res.diagnostics.append(meshes.diagnostics);
    }
    return res;
}

}  // namespace

namespace {
Diagnostics importSwwElevation(const std::string& source, const ImportOptions& o);
}  // namespace

static Diagnostics importElevationImpl(const std::string& source, const ImportOptions& o) {
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

static Diagnostics importImageryImpl(const std::string& source, const ImportOptions& o) {
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
        const int extra = imageryExtraLevels(raw(*src), *w.grid(),
                                             io::StoreWriter::kMaxExtraImageryLevels,
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

std::optional<double> timeFromFileName(const std::string& fileName) {
    static const std::regex re(R"((\d{4})-?(\d{2})-?(\d{2})[T_ -]?(\d{2}):?(\d{2})(?::?(\d{2}))?)");
    std::smatch m;
    const std::string name = fs::path(fileName).filename().string();
    if (!std::regex_search(name, m, re)) return std::nullopt;
    std::string iso = m[1].str() + "-" + m[2].str() + "-" + m[3].str() + "T" + m[4].str() + ":" +
                      m[5].str() + ":" + (m[6].matched ? m[6].str() : std::string("00")) + "Z";
    return parseIso8601(iso);
}

namespace {

std::optional<int> frameNumber(const std::string& file) {
    static const std::regex re(R"((\d+)(?!.*\d))");
    std::smatch m;
    const std::string stem = fs::path(file).stem().string();
    if (!std::regex_search(stem, m, re)) return std::nullopt;
    return int(std::strtol(m[1].str().c_str(), nullptr, 10) % 1000000000L);
}

}  // namespace

Result<std::vector<float>> readCsvGrid(const std::string& path, int& width, int& height) {
    Diagnostics d;
    std::ifstream in(path);
    if (!in) {
        d.error("IMPORT_UNREADABLE", path, "", "cannot read grid");
        return d;
    }
    std::vector<float> values;
    std::string line;
    width = 0;
    height = 0;
    while (std::getline(in, line)) {
        for (char& c : line)
            if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
        std::istringstream ls(line);
        int n = 0;
        std::string tok;
        while (ls >> tok) {
            char* end = nullptr;
            const double v = std::strtod(tok.c_str(), &end);
            if (!end || *end != '\0') {
                auto& e =
                    d.error("IMPORT_UNREADABLE", path, "", "not a numeric grid: '" + tok + "'");
                e.line = height + 1;
                return d;
            }
            values.push_back(float(v));
            ++n;
        }
        if (n == 0) continue;
        if (width == 0) width = n;
        if (n != width) {
            auto& e = d.error(
                "IMPORT_UNREADABLE", path, "",
                "row has " + std::to_string(n) + " values, expected " + std::to_string(width));
            e.line = height + 1;
            return d;
        }
        ++height;
    }
    if (width == 0) {
        d.error("IMPORT_UNREADABLE", path, "", "empty grid");
        return d;
    }
    return values;
}

namespace {

struct Frame {
    std::string file;  ///< what diagnostics name
    std::string open;  ///< what GDAL opens
    int band = 1;
    std::optional<double> time;
    bool csvGrid = false;
};

std::optional<std::string> findLike(const std::string& file) {
    fs::path dir = fs::path(file).parent_path();
    for (int i = 0; i < 3 && !dir.empty(); ++i) {
        std::error_code ec;
        if (fs::exists(dir / "elevation.asc", ec)) return (dir / "elevation.asc").string();
        dir = dir.parent_path();
    }
    return std::nullopt;
}

Result<std::vector<Frame>> expandSources(const std::vector<std::string>& sources,
                                         const ImportOptions& o) {
    Diagnostics d;
    std::vector<Frame> frames;
    std::vector<std::string> files;
    for (const auto& s : sources) {
        std::error_code ec;
        if (fs::is_directory(s, ec)) {
            std::vector<std::string> inDir;
            for (const auto& e : fs::directory_iterator(s, ec))
                if (e.is_regular_file()) inDir.push_back(e.path().string());
            std::sort(inDir.begin(), inDir.end());
            files.insert(files.end(), inDir.begin(), inDir.end());
        } else {
            files.push_back(s);
        }
    }
    for (const auto& f : files) {
        std::error_code ec;
        if (!fs::exists(f, ec)) {
            d.error("IMPORT_UNREADABLE", f, "", "file does not exist");
            return d;
        }
        if (lowerExt(f) == ".csv") {
            frames.push_back({f, f, 1, std::nullopt, true});
            continue;
        }
        const std::string ext = lowerExt(f);
        if (ext == ".nc" || ext == ".nc4" || ext == ".cdf") {
            std::string open = o.variable.empty() ? f : "NETCDF:\"" + f + "\":" + o.variable;
            auto ds = openRaster(open);
            if (!ds) {
                Diagnostics e;
                e.error("IMPORT_UNREADABLE", f, o.variable.empty() ? "" : o.variable,
                        ds.diagnostics.firstError()->message);
                return e;
            }
            const int bands = GDALGetRasterCount(raw(*ds));
            char** md = GDALGetMetadata(raw(*ds), nullptr);
            const char* dimExtra = CSLFetchNameValue(md, "NETCDF_DIM_EXTRA");
            std::string timeDim = "time";
            if (dimExtra) {
                std::string s = dimExtra;
                s.erase(std::remove(s.begin(), s.end(), '{'), s.end());
                s.erase(std::remove(s.begin(), s.end(), '}'), s.end());
                if (!s.empty()) timeDim = s.substr(0, s.find(','));
            }
            const char* units = CSLFetchNameValue(md, (timeDim + "#units").c_str());
            const char* cal = CSLFetchNameValue(md, (timeDim + "#calendar").c_str());
            std::vector<double> values;
            for (int b = 1; b <= bands; ++b) {
                const char* v = GDALGetMetadataItem(GDALGetRasterBand(raw(*ds), b),
                                                    ("NETCDF_DIM_" + timeDim).c_str(), nullptr);
                if (v) values.push_back(std::strtod(v, nullptr));
            }
            if (units && int(values.size()) == bands) {
                auto times = cfTimesToEpoch(values, units, cal ? cal : "standard");
                if (!times) {
                    for (auto item : times.diagnostics.items()) {
                        item.file = f;
                        d.add(item);
                    }
                    return d;
                }
                for (int b = 1; b <= bands; ++b)
                    frames.push_back({f, open, b, (*times)[std::size_t(b - 1)], false});
                continue;
            }
            for (int b = 1; b <= bands; ++b) frames.push_back({f, open, b, std::nullopt, false});
            continue;
        }
        frames.push_back({f, f, 1, std::nullopt, false});
    }
    if (frames.empty()) {
        d.error("IMPORT_USAGE", "", "", "no sequence sources given");
        return d;
    }
    // Times not given by the data: a CSV, a pattern in names, or numbered from --start.
    const bool haveAll =
        std::all_of(frames.begin(), frames.end(), [](const Frame& f) { return bool(f.time); });
    if (o.timesCsv) {
        auto csv = readTimesCsv(*o.timesCsv);
        if (!csv) return csv.diagnostics;
        const bool byName = !csv->front().first.empty();
        if (!byName && csv->size() != frames.size()) {
            d.error("IMPORT_TIMES", *o.timesCsv, "",
                    std::to_string(csv->size()) + " times for " + std::to_string(frames.size()) +
                        " frames");
            return d;
        }
        for (std::size_t i = 0; i < frames.size(); ++i) {
            if (!byName) {
                frames[i].time = (*csv)[i].second;
                continue;
            }
            const std::string name = fs::path(frames[i].file).filename().string();
            auto it = std::find_if(csv->begin(), csv->end(), [&](const auto& e) {
                return fs::path(e.first).filename().string() == name;
            });
            if (it == csv->end()) {
                d.error("IMPORT_TIMES", *o.timesCsv, "", "no time for " + name);
                return d;
            }
            frames[i].time = it->second;
        }
    } else if (!haveAll) {
        for (std::size_t i = 0; i < frames.size(); ++i) {
            if (frames[i].time) continue;
            if (auto t = timeFromFileName(frames[i].file)) {
                frames[i].time = t;
                continue;
            }
            if (o.start) {
                const auto n = frameNumber(frames[i].file);
                const bool multiBand = frames[i].band > 1 || (i + 1 < frames.size() &&
                                                              frames[i + 1].file == frames[i].file);
                const double k = multiBand || !n ? double(i) : double(*n);
                frames[i].time = *o.start + k * o.step;
                continue;
            }
            d.error("IMPORT_NO_TIMES", frames[i].file, "",
                    "no timestamp for this frame (give --times TIMES.csv, --start TIME [--step "
                    "SECONDS], or a date-time in the file name)");
            return d;
        }
    }
    return frames;
}

// The grid of an SWW import (a new store gets one sized to the mesh) and the mesh's window on
// it. Shared by the depth sequence and the bed elevation so both layers sit on one grid.
Result<GridWindow> swwGridWindow(io::StoreWriter& w, const SwwMesh& mesh, const ImportOptions& o,
                                 const std::string& source) {
    Diagnostics e;
    double minX, minY, maxX, maxY;
    mesh.bounds(minX, minY, maxX, maxY);
    if (!w.grid()) {
        StoreCrs crs = localCrs();
        if (o.toCrs) {
            e.error("IMPORT_USAGE", source, "--to-crs",
                    "an SWW mesh is rasterised in its own CRS (name it with --assign-crs)");
            return e;
        }
        if (const auto& given = o.assignCrs ? o.assignCrs : o.crs) {
            auto c = crsFromUser(*given, o.assignCrs ? "--assign-crs" : "--crs");
            if (!c) return c.diagnostics;
            crs = *c;
        } else if (mesh.epsg()) {
            auto c = crsFromUser("EPSG:" + std::to_string(mesh.epsg()));
            if (c) crs = *c;
        }
        const double p = o.pixelSize ? *o.pixelSize : std::max(maxX - minX, maxY - minY) / 512.0;
        const int wpx = int(std::ceil((maxX - minX) / p)), hpx = int(std::ceil((maxY - minY) / p));
        int levels = 1;
        while (std::int64_t(o.tileSize) << (levels - 1) < std::max(wpx, hpx)) ++levels;
        io::TileGrid g;
        g.srsId = crs.srsId;
        g.crsName = crs.name;
        g.crsWkt = crs.wkt;
        g.minX = minX;
        g.maxY = maxY;
        const double size = p * double(std::int64_t(o.tileSize) << (levels - 1));
        g.maxX = minX + size;
        g.minY = maxY - size;
        g.setPyramid(levels, o.tileSize, o.tileSize, p);
        e.append(w.defineGrid(g));
        if (e.hasErrors()) return e;
    }
    const io::TileGrid& g = *w.grid();
    const double p = g.levels.back().pixelXSize;
    const double full = double(g.levels.back().tileWidth) * g.levels.back().matrixWidth;
    GridWindow win;
    win.x0 = int(std::clamp(std::floor((minX - g.minX) / p), 0.0, full));
    win.x1 = int(std::clamp(std::ceil((maxX - g.minX) / p), 0.0, full));
    win.y0 = int(std::clamp(std::floor((g.maxY - maxY) / p), 0.0, full));
    win.y1 = int(std::clamp(std::ceil((g.maxY - minY) / p), 0.0, full));
    if (win.x1 == win.x0 && win.x1 < full) ++win.x1;
    if (win.y1 == win.y0 && win.y1 < full) ++win.y1;
    if (win.empty()) {
        e.error("IMPORT_EXTENT_MISMATCH", source, "",
                "mesh extent does not overlap the store extent");
        return e;
    }
    return win;
}

// `import elevation X.sww`: the model's bed, rasterised on the same grid as its depth sequence
// (a SWW-only store otherwise has no terrain to draw the flood on).
Diagnostics importSwwElevation(const std::string& source, const ImportOptions& o) {
    auto mesh = SwwMesh::open(source);
    if (!mesh) return mesh.diagnostics;
    auto elev = mesh->elevation(0);
    if (!elev) return elev.diagnostics;
    double lo = 1e300, hi = -1e300;
    for (float v : *elev) {
        lo = std::min(lo, double(v) * o.zScale);
        hi = std::max(hi, double(v) * o.zScale);
    }
    if (o.zScale != 1.0)
        for (float& v : *elev) v = float(double(v) * o.zScale);
    Diagnostics warnings;
    Progress progress(o.quiet);
    Diagnostics d = withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        auto win = swwGridWindow(w, *mesh, o, source);
        if (!win) return win.diagnostics;
        PlacedSource ps;
        ps.window = *win;
        ScalarImport si;
        si.table = o.name.empty() ? "elevation" : o.name;
        si.units = "m";
        const double minusInf = -std::numeric_limits<double>::infinity();
        auto rows = mesh->rasterize(*w.grid(), *win, std::move(*elev), minusInf);
        auto r = importScalarLayer(w, ps, rows, std::make_pair(std::min(lo, hi), std::max(lo, hi)),
                                   si, o, source, progress);
        return r.diagnostics;
    });
    warnings.append(d);
    return warnings;
}
Diagnostics importSww(const std::string& source, const ImportOptions& o) {
    // --variable: depth (stage - elevation, the default) or velocity (|momentum| / depth).
    const bool velocity = o.variable == "velocity";
    if (!o.variable.empty() && o.variable != "depth" && !velocity) {
        Diagnostics d;
        d.error(
            "IMPORT_USAGE", source, "--variable",
            "an SWW file gives --variable depth (default) or velocity, not \"" + o.variable + "\"");
        return d;
    }
    auto mesh = SwwMesh::open(source);
    if (!mesh) return mesh.diagnostics;
    if (mesh->steps() < 1) {
        Diagnostics d;
        d.error("IMPORT_SWW", source, "", "no time steps");
        return d;
    }
    std::vector<double> times = mesh->times();
    if (o.start)
        for (auto& t : times) t = t - mesh->startTime() + *o.start;
    {
        Diagnostics d = checkTimes(times, std::vector<std::string>(times.size(), source));
        if (d.hasErrors()) return d;
    }
    Diagnostics warnings;
    Progress progress(o.quiet);
    Diagnostics d = withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        Diagnostics e;
        auto win = swwGridWindow(w, *mesh, o, source);
        if (!win) return win.diagnostics;
        const io::TileGrid& g = *w.grid();
        io::SequenceSpec spec;
        spec.name = o.name;
        spec.units = o.units.value_or(velocity ? "m/s" : "m");
        spec.variable = velocity ? "velocity" : "depth";
        spec.description = (velocity ? "|momentum| / depth from " : "stage - elevation from ") +
                           fs::path(source).filename().string();
        e.append(w.createSequence(spec));
        const auto existing = w.sequenceTimes(o.name);
        if (!existing.empty() && times.front() <= existing.back()) {
            e.error("IMPORT_TIMES_UNSORTED", source, o.name,
                    "first new frame " + formatIso8601(times.front()) +
                        " is not after the sequence's last frame " +
                        formatIso8601(existing.back()));
            return e;
        }
        PlacedSource ps;
        ps.window = *win;
        for (int s = 0; s < mesh->steps(); ++s) {
            auto depth = velocity ? mesh->velocity(s, o.wetThreshold) : mesh->depth(s);
            if (!depth) return depth.diagnostics;
            double lo = 1e300, hi = -1e300;
            for (float v : *depth) {
                const double dv = v < o.wetThreshold ? 0.0 : double(v);
                lo = std::min(lo, dv);
                hi = std::max(hi, dv);
            }
            const int index = int(existing.size()) + s;
            char table[128];
            std::snprintf(table, sizeof table, "%s_f%04d", o.name.c_str(), index);
            ScalarImport si;
            si.table = table;
            si.kind = io::LayerKind::Sequence;
            si.units = spec.units;
            si.minStep = 1.0 / 4096.0;
            auto rows = mesh->rasterize(g, *win, std::move(*depth), o.wetThreshold);
            auto r =
                importScalarLayer(w, ps, rows, std::make_pair(lo, hi), si, o, source, progress);
            if (!r) return r.diagnostics;
            e.append(r.diagnostics);
            e.append(w.addSequenceFrame(o.name, index, times[std::size_t(s)], table, r->minValue,
                                        r->maxValue));
            if (e.hasErrors()) return e;
        }
        return e;
    });
    warnings.append(d);
    return warnings;
}

}  // namespace

static Diagnostics importSequenceImpl(const std::vector<std::string>& sources,
                                      const ImportOptions& o) {
    initGdal();
    Diagnostics d;
    if (o.name.empty()) {
        d.error("IMPORT_USAGE", "", "--name", "sequence needs --name");
        return d;
    }
    if (!io::StoreWriter::validTableName(o.name)) {
        d.error("IMPORT_USAGE", "", "--name",
                "sequence name must be letters, digits and '_' (e.g. flood_depth)");
        return d;
    }
    if (sources.size() == 1 && lowerExt(sources[0]) == ".sww") return importSww(sources[0], o);
    auto frames = expandSources(sources, o);
    if (!frames) return frames.diagnostics;
    {
        std::vector<double> times;
        std::vector<std::string> files;
        for (const auto& f : *frames) {
            times.push_back(*f.time);
            files.push_back(f.file);
        }
        d = checkTimes(times, files);
        if (d.hasErrors()) return d;
    }
    const bool anyCsv =
        std::any_of(frames->begin(), frames->end(), [](const Frame& f) { return f.csvGrid; });
    const bool categorical = o.categorical.value_or(anyCsv);
    std::optional<std::string> like = o.gridLike;
    if (anyCsv && !like) like = findLike(frames->front().file);
    if (anyCsv && !like) {
        d.error("IMPORT_NO_GEOREF", frames->front().file, "",
                "CSV grid has no georeferencing (give --like RASTER with the same grid, e.g. the "
                "landscape's elevation.asc)");
        return d;
    }
    Diagnostics warnings;
    Progress progress(o.quiet);
    d = withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        Diagnostics e;
        io::SequenceSpec spec;
        spec.name = o.name;
        spec.variable = o.variable.empty() ? (anyCsv ? "burn_state" : "value") : o.variable;
        spec.categorical = categorical;
        spec.description = "imported from " + fs::path(frames->front().file).filename().string();
        SequenceUnits units(o.units, w.sequenceUnits(o.name), categorical, o.name,
                            o.store.string());
        e.append(units.start());
        if (e.hasErrors()) return e;
        const auto existing = w.sequenceTimes(o.name);
        if (!existing.empty() && *frames->front().time <= existing.back()) {
            e.error("IMPORT_TIMES_UNSORTED", frames->front().file, o.name,
                    "first new frame " + formatIso8601(*frames->front().time) +
                        " is not after the sequence's last frame " +
                        formatIso8601(existing.back()));
            return e;
        }
        GdalDataset likeDs;
        if (like) {
            auto l = openRaster(*like);
            if (!l) return l.diagnostics;
            likeDs = std::move(*l);
        }
        for (std::size_t i = 0; i < frames->size(); ++i) {
            const Frame& fr = (*frames)[i];
            GdalDataset ds;
            if (fr.csvGrid) {
                int gw = 0, gh = 0;
                auto values = readCsvGrid(fr.file, gw, gh);
                if (!values) return values.diagnostics;
                if (gw != GDALGetRasterXSize(raw(likeDs)) ||
                    gh != GDALGetRasterYSize(raw(likeDs))) {
                    e.error("IMPORT_EXTENT_MISMATCH", fr.file, "",
                            "grid is " + std::to_string(gw) + "x" + std::to_string(gh) + " but " +
                                *like + " is " + std::to_string(GDALGetRasterXSize(raw(likeDs))) +
                                "x" + std::to_string(GDALGetRasterYSize(raw(likeDs))));
                    return e;
                }
                std::array<double, 6> gt{};
                GDALGetGeoTransform(raw(likeDs), gt.data());
                const char* wkt = GDALGetProjectionRef(raw(likeDs));
                ds = memRaster(*values, gw, gh, gt, wkt ? wkt : "", std::nullopt);
            } else {
                auto r = openRaster(fr.open);
                if (!r) return r.diagnostics;
                ds = std::move(*r);
                const std::string where =
                    o.variable.empty() ? "band " + std::to_string(fr.band) : o.variable;
                auto declared = bandUnits(raw(ds), fr.band, fr.file, where);
                if (!declared && !o.units) return declared.diagnostics;
                e.append(units.frame(declared ? *declared : "", fr.file, where));
                if (e.hasErrors()) return e;
            }
            // The sequence records the units its first frame states (or --units).
            if (i == 0) {
                spec.units = units.units();
                e.append(w.createSequence(spec));
                if (e.hasErrors()) return e;
            }
            auto range = bandRange(raw(ds), fr.band);
            if (!range) {
                e.error("IMPORT_ALL_NODATA", fr.file, "band " + std::to_string(fr.band),
                        "frame holds no valid value (all nodata)");
                return e;
            }
            PlaceOptions po = placeOptions(o, fr.file);
            po.nearest = categorical;
            auto ps = placeSource(w, std::move(ds), po, o.tileSize, warnings);
            if (!ps) return ps.diagnostics;
            const int index = int(existing.size() + i);
            char table[128];
            std::snprintf(table, sizeof table, "%s_f%04d", o.name.c_str(), index);
            ScalarImport si;
            si.table = table;
            si.kind = io::LayerKind::Sequence;
            si.units = spec.units;
            si.categorical = categorical;
            si.minStep = 1.0 / 4096.0;
            auto r = importScalarLayer(w, *ps, scalarRows(*ps, fr.band, o.zScale, fr.file), range,
                                       si, o, fr.file, progress);
            if (!r) return r.diagnostics;
            e.append(r.diagnostics);
            e.append(w.addSequenceFrame(o.name, index, *fr.time, table, r->minValue, r->maxValue));
            if (e.hasErrors()) return e;
        }
        return e;
    });
    warnings.append(d);
    return warnings;
}

template <class Fn>
static Diagnostics guarded(const std::string& what, Fn&& fn) {
    try {
        return fn();
    } catch (const std::exception& e) {
        Diagnostics d;
        d.error("IMPORT_INTERNAL", what, "", std::string("import aborted: ") + e.what());
        return d;
    }
}

Diagnostics importElevation(const std::string& source, const ImportOptions& o) {
    return guarded(source, [&] { return importElevationImpl(source, o); });
}

Diagnostics importImagery(const std::string& source, const ImportOptions& o) {
    return guarded(source, [&] { return importImageryImpl(source, o); });
}

Diagnostics importSequence(const std::vector<std::string>& sources, const ImportOptions& o) {
    return guarded(sources.empty() ? std::string() : sources.front(),
                   [&] { return importSequenceImpl(sources, o); });
}

}  // namespace kiosk::import
