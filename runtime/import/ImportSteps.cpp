#include "runtime/import/ImportSteps.h"

#include "runtime/core/TimeParse.h"
#include "runtime/import/GeoTarget.h"
#include "runtime/import/TileMeshes.h"

#include <cctype>
#include <cstdio>
#include <filesystem>

namespace kiosk::import {

namespace fs = std::filesystem;

std::string lowerExt(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

void windowExtent(const io::TileGrid& g, const GridWindow& w, double& x0, double& y0, double& x1,
                  double& y1) {
    const double p = g.levels.back().pixelXSize;
    x0 = g.minX + w.x0 * p;
    x1 = g.minX + w.x1 * p;
    y1 = g.maxY - w.y0 * p;
    y0 = g.maxY - w.y1 * p;
}

Result<PlacedSource> placeSource(io::StoreWriter& w, GdalDataset src, const PlaceOptions& po,
                                 int tileSize, Diagnostics& warnings, const io::TileGrid* onGrid) {
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

Diagnostics checkAppendsAfter(const std::vector<double>& existing, double firstNew,
                              const std::string& file, const std::string& sequence) {
    Diagnostics d;
    if (!existing.empty() && firstNew <= existing.back())
        d.error("IMPORT_TIMES_UNSORTED", file, sequence,
                "first new frame " + formatIso8601(firstNew) +
                    " is not after the sequence's last frame " + formatIso8601(existing.back()));
    return d;
}

Diagnostics importSequenceFrame(io::StoreWriter& w, const PlacedSource& ps,
                                const ScalarRowSource& rows,
                                std::optional<std::pair<double, double>> range,
                                const std::string& sequence, int index, double epochSeconds,
                                const std::string& units, bool categorical, const ImportOptions& o,
                                const std::string& src, Progress& progress) {
    char table[128];
    std::snprintf(table, sizeof table, "%s_f%04d", sequence.c_str(), index);
    ScalarImport si;
    si.table = table;
    si.kind = io::LayerKind::Sequence;
    si.units = units;
    si.categorical = categorical;
    si.minStep = 1.0 / 4096.0;
    auto r = importScalarLayer(w, ps, rows, range, si, o, src, progress);
    if (!r) return r.diagnostics;
    Diagnostics d = r.diagnostics;
    d.append(w.addSequenceFrame(sequence, index, epochSeconds, table, r->minValue, r->maxValue));
    return d;
}

}  // namespace kiosk::import
