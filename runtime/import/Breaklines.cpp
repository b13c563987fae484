// `geokiosk import breaklines`: lines read with GDAL/OGR, TINs built by LocalTins.h.
#include "runtime/import/GdalRaster.h"
#include "runtime/import/LocalTinImport.h"
#include "runtime/import/LocalTins.h"
#include "runtime/import/TempStore.h"

#include <cpl_error.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <limits>
#include <memory>

namespace kiosk::import {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

struct ReadLines {
    std::vector<std::vector<glm::dvec3>> lines3d, lines2d;  // 2D: z NaN until the DEM gives it
    std::size_t features = 0;
};

void addLine(const OGRLineString& l, bool hasZ, ReadLines& out) {
    std::vector<glm::dvec3> pts;
    pts.reserve(std::size_t(l.getNumPoints()));
    for (int i = 0; i < l.getNumPoints(); ++i)
        pts.emplace_back(l.getX(i), l.getY(i), hasZ ? l.getZ(i) : kNan);
    if (pts.size() >= 2) (hasZ ? out.lines3d : out.lines2d).push_back(std::move(pts));
}

Result<ReadLines> readLines(const std::string& path, const std::string& storeWkt) {
    Diagnostics d;
    initGdal();
    CPLErrorReset();
    std::unique_ptr<GDALDataset> ds(
        GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) {
        const std::string why = CPLGetLastErrorMsg();
        d.error("IMPORT_UNREADABLE", path, "",
                "cannot read lines from it" + (why.empty() ? std::string() : ": " + why));
        return d;
    }
    OGRSpatialReference target;
    target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (target.importFromWkt(storeWkt.c_str()) != OGRERR_NONE) {
        d.error("IMPORT_BREAKLINES", path, "",
                "the store's CRS cannot be read to reproject the lines into");
        return d;
    }
    ReadLines out;
    for (OGRLayer* layer : ds->GetLayers()) {
        const std::string lname = layer->GetName();
        const OGRSpatialReference* srs = layer->GetSpatialRef();
        // A GeoPackage layer of srs_id 0 or -1 reads as GDAL's "Undefined geographic SRS" /
        // "Undefined Cartesian SRS": no CRS either.
        const std::string srsName = srs && srs->GetName() ? srs->GetName() : "";
        if (!srs || srsName.rfind("Undefined ", 0) == 0) {
            d.error(
                "IMPORT_NO_CRS", path, lname,
                "layer has no CRS: the lines cannot be placed in the store (give the file a CRS, "
                "e.g. ogr2ogr -a_srs EPSG:N)");
            return d;
        }
        OGRSpatialReference source(*srs);
        source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        std::unique_ptr<OGRCoordinateTransformation> ct;
        if (!source.IsSame(&target)) {
            ct.reset(OGRCreateCoordinateTransformation(&source, &target));
            if (!ct) {
                d.error("IMPORT_BREAKLINES", path, lname,
                        "cannot reproject the layer's CRS (" +
                            std::string(srs->GetName() ? srs->GetName() : "?") +
                            ") into the store's");
                return d;
            }
        }
        for (auto& feature : *layer) {
            ++out.features;
            OGRGeometry* g = feature->GetGeometryRef();
            if (!g) continue;  // a feature without geometry carries no line
            const std::string where = lname + " feature " + std::to_string(feature->GetFID());
            if (ct && g->transform(ct.get()) != OGRERR_NONE) {
                d.error("IMPORT_BREAKLINES", path, where,
                        "a coordinate does not reproject into the store's CRS");
                return d;
            }
            const bool hasZ = g->Is3D();
            const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
            if (type == wkbLineString) {
                addLine(*g->toLineString(), hasZ, out);
            } else if (type == wkbMultiLineString) {
                for (const OGRLineString* l : *g->toMultiLineString()) addLine(*l, hasZ, out);
            } else {
                d.error("IMPORT_BREAKLINES", path, where,
                        std::string("is a ") + OGRGeometryTypeToName(type) +
                            ", not a line (breaklines are LineString or MultiLineString)");
                return d;
            }
        }
    }
    if (out.lines2d.empty() && out.lines3d.empty()) {
        d.error("IMPORT_BREAKLINES", path, "", "holds no line (LineString or MultiLineString)");
        return d;
    }
    return out;
}

}  // namespace

Diagnostics importBreaklines(const std::string& path, const LocalTinImportOptions& o) {
    return withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        Diagnostics d;
        if (!w.grid() || !w.hasTable(o.elevation)) {
            d.error(
                "IMPORT_NO_ELEVATION", o.store.string(), o.elevation,
                "store has no elevation layer \"" + o.elevation + "\" (import elevation first)");
            return d;
        }
        auto lines = readLines(path, w.grid()->crsWkt);
        if (!lines) return lines.diagnostics;
        TinFeatures f;
        f.lines = std::move(lines->lines3d);
        if (!lines->lines2d.empty()) {
            d.append(heightsFromElevation(w, o.elevation, lines->lines2d));
            if (d.hasErrors()) return d;
            for (auto& l : lines->lines2d) f.lines.push_back(std::move(l));
        }
        if (f.lines.empty()) {
            d.error("IMPORT_TIN_OUTSIDE", path, "",
                    "no 2D line lies over the elevation's data (wrong CRS, or lines outside the "
                    "store)");
            return d;
        }
        LocalTinOptions lo;
        lo.elevation = o.elevation;
        lo.source = o.name;
        lo.threads = o.threads;
        Progress progress(o.quiet);
        auto stats = storeLocalTins(w, f, lo, progress);
        for (Diagnostic e : stats.diagnostics.items()) {
            if (e.code == "IMPORT_TIN_OUTSIDE") e.file = path;
            d.add(std::move(e));
        }
        if (stats.ok() && !o.quiet)
            std::fprintf(stderr,
                         "geokiosk: %lld TIN tiles (levels %d..%d), %lld triangles (their grid "
                         "meshes: %lld), %lld bytes, worst post %.3f m off\n",
                         (long long)stats->tiles, stats->coarsestLevel, stats->finestLevel,
                         (long long)stats->tinTriangles, (long long)stats->gridTriangles,
                         (long long)stats->blobBytes, stats->maxError);
        return d;
    });
}

}  // namespace kiosk::import
