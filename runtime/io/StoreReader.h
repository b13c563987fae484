#pragma once

#include "runtime/core/Result.h"
#include "runtime/io/MeshBlob.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/io/TextureBlocks.h"
#include "runtime/io/TinBlob.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace kiosk::io {

/**
 * @brief Read-only access to one geokiosk store (a GeoPackage 1.3 file).
 *
 * Threads: one StoreReader per thread (each owns a read-only SQLite connection opened with
 * SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX and its own prepared statements). Safe while another
 * process appends to the store in WAL mode. Never throws. A missing or corrupt tile is an error
 * for that tile only (code STORE_TILE_MISSING / STORE_TILE_CORRUPT naming layer and tile).
 */
class StoreReader {
public:
    virtual ~StoreReader() = default;

    /** @brief Open and read the metadata; errors name the file (STORE_OPEN, STORE_NOT_GEOKIOSK). */
    static Result<std::unique_ptr<StoreReader>> open(const std::filesystem::path& path);

    virtual const StoreInfo& info() const noexcept = 0;

    /**
     * @brief Page cache of each connection opened from now on (a kiosk's
     * budgets.sqlitePageCacheBytes; default kDefaultPageCacheBytes). Any thread.
     */
    static void setPageCacheBytes(std::int64_t bytes);
    static std::int64_t pageCacheBytes();
    /** @brief Store connections open now (the page cache budget in use is this many times it). */
    static int openConnections();
    /** @brief Tiles are blobs read once each; the b-tree pages leading to them fit in 256 KiB. */
    static constexpr std::int64_t kDefaultPageCacheBytes = 256 << 10;

    /** @brief Elevation posts of one tile, decoded to metres (scale/offset applied). */
    virtual Result<RasterTile> readElevation(const std::string& layer, const TileId& id) = 0;
    /** @brief Imagery tile as RGBA8. */
    virtual Result<ImageTile> readImagery(const std::string& layer, const TileId& id) = 0;
    /** @brief One frame of a sequence, decoded to data units; same post layout as elevation. */
    virtual Result<RasterTile> readSequenceFrame(const std::string& sequence, int frame,
                                                 const TileId& id) = 0;
    /** @brief Min/max/error of a tile without decoding it; nullopt if the tile is absent. */
    virtual std::optional<TileStats> tileStats(const std::string& layer, const TileId& id) = 0;
    /**
     * @brief The mesh stored for an elevation tile at import (kiosk_tile_meshes), into `out`
     * (its buffers reused): the one of `tolerance`, or the tier-0 one of `baseTolerance` with
     * split tiers to derive it from (TileQueries::readMesh); false when there is neither (stores
     * imported before meshes were stored, other tolerances): the caller meshes the posts.
     * STORE_MESH_CORRUPT when the blob does not decode.
     */
    virtual Result<bool> readTileMesh(const std::string& layer, const TileId& id, double tolerance,
                                      double baseTolerance, TileMeshRow& out) {
        (void)layer, (void)id, (void)tolerance, (void)baseTolerance, (void)out;
        return false;
    }
    /**
     * @brief An imagery tile's GPU blocks of `format` stored at import (kiosk_tile_textures),
     * into `out` (its buffer reused), not decoded; false when the store has none for the tile
     * (the caller reads the PNG). STORE_TEXTURE_CORRUPT when the row's sizes and blob disagree.
     */
    virtual Result<bool> readTileTexture(const std::string& layer, const TileId& id,
                                         TextureFormat format, CompressedImage& out) {
        (void)layer, (void)id, (void)format, (void)out;
        return false;
    }
    /**
     * @brief The coarsest local TIN stored for an elevation tile within `tolerance`
     * (kiosk_tile_tins), into `out` (its buffers reused); false when the tile has none that
     * fine. STORE_TIN_CORRUPT when it does not decode.
     */
    virtual Result<bool> readTileTin(const std::string& layer, const TileId& id, double tolerance,
                                     TileTinRow& out) {
        (void)layer, (void)id, (void)tolerance, (void)out;
        return false;
    }
};

}  // namespace kiosk::io
