// ANUGA SWW models: the bed as elevation, depth or velocity as a sequence, on one grid.
#include "runtime/core/TimeParse.h"
#include "runtime/import/GeoTarget.h"
#include "runtime/import/ImportSteps.h"
#include "runtime/import/SwwMesh.h"
#include "runtime/import/TempStore.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

namespace kiosk::import {

namespace fs = std::filesystem;

namespace {

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

}  // namespace

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
        e.append(checkAppendsAfter(existing, times.front(), source, o.name));
        if (e.hasErrors()) return e;
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
            auto rows = mesh->rasterize(g, *win, std::move(*depth), o.wetThreshold);
            e.append(importSequenceFrame(w, ps, rows, std::make_pair(lo, hi), o.name,
                                         int(existing.size()) + s, times[std::size_t(s)],
                                         spec.units, false, o, source, progress));
            if (e.hasErrors()) return e;
        }
        return e;
    });
    warnings.append(d);
    return warnings;
}

}  // namespace kiosk::import
