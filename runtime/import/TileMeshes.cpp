#include "runtime/import/TileMeshes.h"

#include "runtime/io/MeshBlob.h"
#include "runtime/terrain/RtinMesher.h"
#include "runtime/terrain/StoredMesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

/**
 * Mesh `job.posts` at tolerance tier `tier`; append it unless it has more than `maxVertices`
 * (tier 0: with split tiers when `exact`). False on an error (in job.diagnostics).
 */
bool meshTier(TileJob& job, const io::TileGrid& grid, const terrain::TerrainOptions& options,
              double zStep, int tier, bool exact, std::size_t maxVertices,
              terrain::RtinMesher& mesher, terrain::TileMesh& mesh) {
    terrain::MeshParams p = terrain::MeshParams::forTile(
        grid, job.posts.id, options, double(job.posts.stats.geometricError), tier);
    p.skirtDepth = 0.0;  // skirts depend on the run; the loader adds them
    Diagnostics d = mesher.build(job.posts, p, mesh);
    if (d.hasErrors()) {
        job.diagnostics = std::move(d);
        return false;
    }
    if (mesh.vertexCount() > maxVertices) return true;
    auto q = terrain::quantizeSurface(mesh, zStep);
    if (!q) {
        job.diagnostics = std::move(q.diagnostics);
        return false;
    }
    if (exact) q->splitTiers = terrain::splitTiersOf(mesher, p.tolerance);
    job.tiers.push_back({tier, p.tolerance, mesh.vertexCount(), mesh.triangleCount(), exact,
                         io::encodeMeshBlob(*q)});
    return true;
}

void meshTile(TileJob& job, const io::TileGrid& grid, const terrain::TerrainOptions& options,
              double zStep, terrain::RtinMesher& mesher, terrain::TileMesh& mesh) {
    const bool nodata = std::any_of(job.posts.values.begin(), job.posts.values.end(),
                                    [](float v) { return std::isnan(v); });
    // Without nodata every coarser tier follows from tier 0 and its vertices' split tiers (exact
    // split errors). Next to nodata a split can hinge on a post that is no vertex: such tiles
    // keep their coarser tiers whole, each meshed as the loader would mesh it, else the loader
    // meshes them from the posts on every start (the demo's distant tiles, 20-50 ms each;
    // docs/performance.md §5.2). Only tiers with at most half of tier 0's vertices: every tier
    // made the demo store 2.5 times larger (21 -> 52 MB), these 1.27 times (27 MB), and the
    // finer ones are the nearby tiles' (tier 0 derived or meshed on load, as before).
    mesher.setExactErrors(!nodata);
    const std::size_t any = std::numeric_limits<std::size_t>::max();
    if (!meshTier(job, grid, options, zStep, 0, !nodata, any, mesher, mesh) || !nodata) {
        job.posts.values = {};
        return;
    }
    const std::size_t half = job.tiers.front().vertices / 2;
    for (int tier = 1; tier <= options.maxToleranceTier(); ++tier)
        if (!meshTier(job, grid, options, zStep, tier, false, half, mesher, mesh)) {
            job.tiers.clear();  // a tile keeps all its tiers or none
            break;
        }
    job.posts.values = {};
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
