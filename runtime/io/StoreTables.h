#pragma once

#include "runtime/core/Result.h"
#include "runtime/io/MeshBlob.h"
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/io/TextureBlocks.h"
#include "runtime/io/TinBlob.h"

#include <map>
#include <optional>
#include <string>

// Table and extension names of the geokiosk store (docs/store-format.md) and the tile queries
// shared by StoreReader and StoreWriter.
namespace kiosk::io {

inline constexpr const char* kGridTable = "kiosk_grid";
inline constexpr const char* kLayersTable = "kiosk_layers";
inline constexpr const char* kTileStatsTable = "kiosk_tile_stats";
inline constexpr const char* kSequencesTable = "kiosk_sequences";
inline constexpr const char* kFramesTable = "kiosk_sequence_frames";
inline constexpr const char* kStoreExtension = "kiosk_store";
inline constexpr const char* kTileStatsExtension = "kiosk_tile_stats";
inline constexpr const char* kSequencesExtension = "kiosk_sequences";
inline constexpr const char* kTileMeshesTable = "kiosk_tile_meshes";
inline constexpr const char* kTileMeshesExtension = "kiosk_tile_meshes";
inline constexpr const char* kTileTinsTable = "kiosk_tile_tins";
inline constexpr const char* kTileTinsExtension = "kiosk_tile_tins";
inline constexpr const char* kTileTexturesTable = "kiosk_tile_textures";
inline constexpr const char* kTileTexturesExtension = "kiosk_tile_textures";
inline constexpr const char* kCoverageExtension = "gpkg_2d_gridded_coverage";
/** @brief The OGC specification of the gridded coverage extension (gpkg_extensions.definition). */
inline constexpr const char* kCoverageDefinition =
    "http://docs.opengeospatial.org/is/17-066r1/17-066r1.html";
/** @brief gpkg_extensions.definition of our extensions (plus "#extension_name"). */
inline constexpr const char* kOurDefinition = "https://geokiosk.invalid/docs/store-format.md";
inline constexpr std::int32_t kGpkgApplicationId = 0x47504B47;  // 'GPKG'
inline constexpr int kGpkgUserVersion = 10300;

/** @brief Layer kind as stored in kiosk_layers.kind. */
const char* layerKindName(LayerKind kind) noexcept;
std::optional<LayerKind> parseLayerKind(const std::string& name) noexcept;

/**
 * @brief Reads tiles of one connection with cached prepared statements (one per table).
 * Not thread-safe (one per connection). Table names must come from kiosk_layers.
 */
class TileQueries {
public:
    explicit TileQueries(SqliteDb& db) : mDb(&db) {}

    struct ScalarMeta {
        int tileWidth = 256;
        int tileHeight = 256;
        double dataNull = 65535;
        double coverageScale = 1.0;
        double coverageOffset = 0.0;
    };

    /** @brief Decode the posts of a scalar tile; STORE_TILE_MISSING / STORE_TILE_CORRUPT. */
    Result<RasterTile> readScalar(const std::string& table, const ScalarMeta& meta,
                                  const TileId& id);
    /** @brief Decode an imagery tile to RGBA8 (RGB or RGBA PNG only when `rgb`). */
    Result<ImageTile> readImage(const std::string& table, const TileId& id, bool rgb = false);
    /**
     * @brief Into `out` (buffers reused): the stored mesh of a tile simplified with `tolerance`,
     * or else its tier-0 mesh of `baseTolerance` when that carries split tiers (the caller
     * derives the tier); false when there is neither (kiosk_tile_meshes). Only a row that is
     * used gets decoded; one that does not decode is STORE_MESH_CORRUPT naming tile and tier.
     */
    Result<bool> readMesh(const std::string& table, const TileId& id, double tolerance,
                          double baseTolerance, TileMeshRow& out);
    /**
     * @brief Into `out` (buffers reused): the coarsest local TIN of a tile built within
     * `tolerance` (kiosk_tile_tins, StoreTinQueries.cpp); false when the tile has none that
     * fine. One that does not decode is STORE_TIN_CORRUPT naming the tile and tier.
     */
    Result<bool> readTin(const std::string& table, const TileId& id, double tolerance,
                         TileTinRow& out);
    /**
     * @brief Into `out` (buffer reused): a tile's GPU blocks of `format` (kiosk_tile_textures,
     * StoreTextureQueries.cpp); false when the tile has none. A row whose sizes do not agree
     * with its blob is STORE_TEXTURE_CORRUPT naming the tile.
     */
    Result<bool> readTexture(const std::string& table, const TileId& id, TextureFormat format,
                             CompressedImage& out);
    /** @brief Stats row, nullopt if absent. */
    std::optional<TileStats> stats(const std::string& table, const TileId& id);

private:
    Statement* statement(std::map<std::string, Statement>& cache, const std::string& key,
                         const std::string& sql, Diagnostics& d);

    SqliteDb* mDb;
    std::map<std::string, Statement> mScalar, mImage;
    Statement mStats, mMesh, mTin, mTexture;
};

/** @brief `table/level/column/row`, the `where` of tile diagnostics. */
std::string tileName(const std::string& table, const TileId& id);

}  // namespace kiosk::io
