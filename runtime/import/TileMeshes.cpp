#include "runtime/import/TileMeshes.h"

#include "runtime/io/MeshBlob.h"
#include "runtime/terrain/RtinMesher.h"
#include "runtime/terrain/StoredMesh.h"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

namespace kiosk::import {

namespace {

struct MeshTier {
    int tier = 0;
    double tolerance = 0.0;
    std::size_t vertices = 0, triangles = 0;
    bool splitTiers = false;
    std::vector<std::uint8_t> blob;
};

struct TileJob {
    io::RasterTile posts;
    std::vector<MeshTier> tiers;
    Diagnostics diagnostics;
};

void meshTile(TileJob& job, const io::TileGrid& grid, const terrain::TerrainOptions& options,
              double zStep, terrain::RtinMesher& mesher, terrain::TileMesh& mesh) {
    const bool nodata = std::any_of(job.posts.values.begin(), job.posts.values.end(),
                                    [](float v) { return std::isnan(v); });
    // Without nodata every coarser tier follows from tier 0 and its vertices' split tiers (exact
    // split errors). Next to nodata a split can hinge on a post that is no vertex: such tiles
    // keep tier 0 only and their coarser tiers are meshed on load (storing each tier whole
    // made the demo store 5.7 times larger).
    mesher.setExactErrors(!nodata);
    terrain::MeshParams p = terrain::MeshParams::forTile(grid, job.posts.id, options,
                                                         double(job.posts.stats.geometricError), 0);
    p.skirtDepth = 0.0;  // skirts depend on the run; the loader adds them
    Diagnostics d = mesher.build(job.posts, p, mesh);
    job.posts.values = {};
    if (d.hasErrors()) {
        job.diagnostics = std::move(d);
        return;
    }
    auto q = terrain::quantizeSurface(mesh, zStep);
    if (!q) {
        job.diagnostics = std::move(q.diagnostics);
        return;
    }
    if (!nodata) q->splitTiers = terrain::splitTiersOf(mesher, p.tolerance);
    job.tiers.push_back({0, p.tolerance, mesh.vertexCount(), mesh.triangleCount(), !nodata,
                         io::encodeMeshBlob(*q)});
}

}  // namespace

Result<TileMeshStats> storeTileMeshes(io::StoreWriter& writer, const std::string& table,
                                      double zStep, int threads, Progress& progress) {
    Diagnostics d = writer.createTileMeshes();
    if (d.hasErrors()) return d;
    auto ids = writer.tileIds(table);
    if (!ids) return ids.diagnostics;
    const io::TileGrid& grid = *writer.grid();
    // The loader's defaults (TerrainScene keeps the tolerance knobs at their defaults).
    const terrain::TerrainOptions options;
    const int workers = std::max(1, threads);
    std::vector<terrain::RtinMesher> meshers(static_cast<std::size_t>(workers));
    std::vector<terrain::TileMesh> meshes(static_cast<std::size_t>(workers));
    TileMeshStats stats;
    std::string firstReason;
    progress.begin(table + " meshes", std::int64_t(ids->size()));
    // Batches bound memory (a few tiles of posts per worker) and keep SQLite on this thread.
    const std::size_t batch = std::size_t(workers) * 8;
    std::vector<TileJob> jobs;
    for (std::size_t start = 0; start < ids->size(); start += batch) {
        const std::size_t end = std::min(ids->size(), start + batch);
        jobs.clear();
        jobs.resize(end - start);
        for (std::size_t i = start; i < end; ++i) {
            auto posts = writer.readScalarTile(table, (*ids)[i]);
            if (!posts) return posts.diagnostics;
            jobs[i - start].posts = std::move(*posts.value);
        }
        std::vector<std::thread> pool;
        for (int w = 0; w < workers; ++w)
            pool.emplace_back([&, w] {
                for (std::size_t j = std::size_t(w); j < jobs.size(); j += std::size_t(workers))
                    meshTile(jobs[j], grid, options, zStep, meshers[std::size_t(w)],
                             meshes[std::size_t(w)]);
            });
        for (auto& t : pool) t.join();
        for (std::size_t j = 0; j < jobs.size(); ++j) {
            const TileId& id = (*ids)[start + j];
            if (jobs[j].tiers.empty()) {
                if (firstReason.empty() && jobs[j].diagnostics.firstError())
                    firstReason =
                        io::tileName(table, id) + ": " + jobs[j].diagnostics.firstError()->message;
                ++stats.skipped;
                continue;
            }
            for (const MeshTier& m : jobs[j].tiers) {
                Diagnostics w = writer.putTileMesh(table, id, m.tier, m.tolerance, m.vertices,
                                                   m.triangles, m.splitTiers, m.blob);
                if (w.hasErrors()) return w;
                ++stats.rows;
                stats.blobBytes += std::int64_t(m.blob.size());
            }
            ++stats.tiles;
        }
        progress.advance(std::int64_t(jobs.size()));
    }
    progress.finish();
    if (stats.skipped > 0)
        d.warning("IMPORT_MESH_SKIPPED", writer.path(), table,
                  std::to_string(stats.skipped) +
                      " tiles keep no stored mesh (meshed on load instead), first " + firstReason);
    return Result<TileMeshStats>(stats, std::move(d));
}

}  // namespace kiosk::import
