// `geokiosk import model-mesh`: an ANUGA SWW mesh (SwwMesh.h, the reader `import sequence`
// uses) as local TINs (LocalTins.h).
#include "runtime/import/GdalRaster.h"
#include "runtime/import/LocalTinImport.h"
#include "runtime/import/LocalTins.h"
#include "runtime/import/SwwMesh.h"
#include "runtime/import/TempStore.h"

#include <set>
#include <utility>

namespace kiosk::import {

Diagnostics importModelMesh(const std::string& path, const LocalTinImportOptions& o) {
    auto mesh = SwwMesh::open(path);
    if (!mesh) return mesh.diagnostics;
    auto bed = mesh->elevation(0);
    if (!bed) return bed.diagnostics;
    TinFeatures f;
    f.meshPoints.reserve(mesh->points());
    for (std::size_t i = 0; i < mesh->points(); ++i)
        f.meshPoints.emplace_back(mesh->x(i), mesh->y(i), double((*bed)[i]));
    const std::vector<int>& tri = mesh->triangleIndices();
    f.meshTriangles.assign(tri.begin(), tri.end());
    // Every triangle edge once: the constrained edges that make the TIN the model's triangles.
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (std::size_t t = 0; t + 2 < f.meshTriangles.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            std::uint32_t a = f.meshTriangles[t + std::size_t(k)];
            std::uint32_t b = f.meshTriangles[t + std::size_t((k + 1) % 3)];
            if (a > b) std::swap(a, b);
            if (a != b && edges.insert({a, b}).second)
                f.lines.push_back({f.meshPoints[a], f.meshPoints[b]});
        }
    return withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        Diagnostics d;
        if (w.grid() && mesh->epsg() &&
            !sameCrs("EPSG:" + std::to_string(mesh->epsg()), w.grid()->crsWkt)) {
            d.error("IMPORT_CRS_MISMATCH", path, "",
                    "the model's UTM zone (EPSG:" + std::to_string(mesh->epsg()) +
                        ") is not the store's CRS (" + w.grid()->crsName + ")");
            return d;
        }
        LocalTinOptions lo;
        lo.elevation = o.elevation;
        lo.source = o.name;
        lo.everyFinestTile = true;
        lo.threads = o.threads;
        Progress progress(o.quiet);
        auto stats = storeLocalTins(w, f, lo, progress);
        for (Diagnostic e : stats.diagnostics.items()) {
            if (e.code == "IMPORT_TIN_OUTSIDE") {
                e.file = path;
                e.message = "the model mesh covers no tile of the elevation layer that has data";
            }
            d.add(std::move(e));
        }
        if (stats.ok() && !o.quiet)
            std::fprintf(stderr,
                         "geokiosk: %zu model triangles -> %lld TIN tiles (levels %d..%d), %lld "
                         "triangles (their grid meshes: %lld), %lld bytes\n",
                         mesh->triangles(), (long long)stats->tiles, stats->coarsestLevel,
                         stats->finestLevel, (long long)stats->tinTriangles,
                         (long long)stats->gridTriangles, (long long)stats->blobBytes);
        return d;
    });
}

}  // namespace kiosk::import
