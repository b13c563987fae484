// Load-to-drawable time per elevation tile and store size: meshes stored at import
// (kiosk_tile_meshes, decoded by the loader) against meshing the posts on load (the same store
// with the table dropped, as stores imported before issue 20). Same run, same tiles, same
// loader code. Prints one JSON object on stdout.
//
//   bench-meshes [STORE...]   (default data/generated/rainier.gpkg)
//
// Load-to-drawable = StoreTileLoader::load of the elevation key: SQLite read + decode +
// skirts (stored) or SQLite read + PNG decode + RTIN meshing + skirts (on load); the GPU upload
// that follows is the same for both. Passes alternate between the paths; the fastest counts.
#include "runtime/io/MeshBlob.h"
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreTables.h"
#include "runtime/loader/StoreTileLoader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace kiosk;
using Clock = std::chrono::steady_clock;

namespace {

struct Pass {
    double msPerTile = 0;
    std::size_t triangles = 0;
};

// Passes alternate between the two paths so a busy machine slows both alike; the first pass of
// each warms SQLite's and the kernel's caches and is not counted.
std::pair<Pass, Pass> loadBoth(const fs::path& with, const fs::path& without,
                               const std::vector<TileId>& ids, int tier) {
    auto open = [](fs::path p) {
        return std::make_unique<loader::StoreTileLoader>(
            [p] { return io::StoreReader::open(p); },
            std::vector<loader::LayerBinding>{{"elevation", io::LayerKind::Elevation}},
            terrain::TerrainOptions{});
    };
    auto loaders = std::array{open(with), open(without)};
    std::array<Pass, 2> best;
    for (auto& l : loaders) l->threadStarted();
    for (auto& b : best) b.msPerTile = 1e30;
    for (int pass = 0; pass < 6; ++pass)
        for (int k = 0; k < 2; ++k) {
            std::size_t triangles = 0;
            const auto t0 = Clock::now();
            for (const TileId& id : ids) {
                loader::LoadRequest r;
                r.key.id = id;
                r.key.frame = tier;
                const terrain::TilePayload p = loaders[std::size_t(k)]->load(r);
                if (p.mesh) triangles += p.mesh->surfaceTriangleCount();
            }
            const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count() /
                              double(ids.size());
            if (pass > 0 && ms < best[std::size_t(k)].msPerTile)
                best[std::size_t(k)] = {ms, triangles};
        }
    for (auto& l : loaders) l->threadStopping();
    return {best[0], best[1]};
}

nlohmann::json benchStore(const fs::path& source, const fs::path& work) {
    nlohmann::json out;
    out["store"] = source.filename().string();
    const fs::path with = work / "with_meshes.gpkg", without = work / "without_meshes.gpkg";
    fs::copy_file(source, with, fs::copy_options::overwrite_existing);
    fs::copy_file(source, without, fs::copy_options::overwrite_existing);
    std::vector<TileId> ids;
    double blobBytes = 0, decodeSeconds = 0, decodedBytes = 0;
    std::int64_t rows = 0;
    {
        auto db = io::SqliteDb::open(with, io::SqliteDb::Mode::ReadWrite);
        if (!db || !db->tableExists(io::kTileMeshesTable)) {
            out["skipped"] = "store has no kiosk_tile_meshes (import it again)";
            return out;
        }
        (void)db->exec("VACUUM");
        auto st = db->prepare("SELECT zoom_level, tile_column, tile_row FROM elevation");
        while (st && st->step() == SQLITE_ROW)
            ids.push_back(
                TileId{int(st->columnInt(0)), int(st->columnInt(1)), int(st->columnInt(2))});
        // Decode speed of the codec alone, over every stored row.
        auto m = db->prepare("SELECT mesh FROM kiosk_tile_meshes");
        while (m && m->step() == SQLITE_ROW) {
            const auto [data, size] = m->columnBlob(0);
            const auto t0 = Clock::now();
            auto q = io::decodeMeshBlob(data, size, "bench");
            decodeSeconds += std::chrono::duration<double>(Clock::now() - t0).count();
            if (!q) continue;
            blobBytes += double(size);
            // What it decodes to: 24-byte float vertices and uint32 indices, as drawn.
            decodedBytes += double(q->vertexCount() * 24 + q->indices.size() * 4);
            ++rows;
        }
    }
    {
        auto db = io::SqliteDb::open(without, io::SqliteDb::Mode::ReadWrite);
        (void)db->exec(
            "DROP TABLE kiosk_tile_meshes; DELETE FROM gpkg_extensions WHERE "
            "table_name = 'kiosk_tile_meshes'; VACUUM");
    }
    out["tiles"] = ids.size();
    out["mesh_rows"] = rows;
    out["store_bytes_with_meshes"] = fs::file_size(with);
    out["store_bytes_without_meshes"] = fs::file_size(without);
    out["mesh_blob_bytes"] = blobBytes;
    out["decode_mb_per_s_compressed"] = blobBytes / 1e6 / std::max(decodeSeconds, 1e-9);
    out["decode_mb_per_s_output"] = decodedBytes / 1e6 / std::max(decodeSeconds, 1e-9);
    for (int tier : {0, 2}) {
        const auto [stored, onLoad] = loadBoth(with, without, ids, tier);
        nlohmann::json t;
        t["stored_ms_per_tile"] = stored.msPerTile;
        t["meshed_on_load_ms_per_tile"] = onLoad.msPerTile;
        t["speedup"] = onLoad.msPerTile / std::max(stored.msPerTile, 1e-9);
        t["same_triangle_count"] = stored.triangles == onLoad.triangles;
        t["triangles"] = stored.triangles;
        out["tier_" + std::to_string(tier)] = t;
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<fs::path> stores;
    for (int i = 1; i < argc; ++i) stores.emplace_back(argv[i]);
    if (stores.empty()) stores.emplace_back("data/generated/rainier.gpkg");
    const fs::path work = fs::temp_directory_path() / "geokiosk-bench-meshes";
    fs::create_directories(work);
    nlohmann::json out;
    out["benchmark"] = "stored_meshes";
    out["baseline"] = "meshed_on_load (same store without kiosk_tile_meshes)";
    for (const fs::path& s : stores) {
        if (!fs::exists(s)) {
            out["stores"].push_back({{"store", s.string()}, {"skipped", "not found"}});
            continue;
        }
        out["stores"].push_back(benchStore(s, work));
    }
    fs::remove_all(work);
    std::cout << out.dump() << "\n";
    return 0;
}
