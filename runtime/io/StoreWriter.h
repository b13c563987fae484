#pragma once

#include "runtime/core/Result.h"
#include "runtime/io/ScalarTileCodec.h"
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreTables.h"
#include "runtime/io/StoreTypes.h"

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace kiosk::io {

/** @brief What a new scalar (2D gridded coverage) tile table holds. */
struct ScalarLayerSpec {
    std::string table;  ///< [A-Za-z_][A-Za-z0-9_]*
    LayerKind kind = LayerKind::Elevation;
    std::string units = "m";
    std::string description;
    double scale = 0.125;          ///< quantisation step (power of two), the declared precision
    std::optional<double> nodata;  ///< source nodata, informative
};

struct SequenceSpec {
    std::string name;
    std::string units;
    std::string variable;
    bool categorical = false;
    std::optional<double> nodata;
    std::string description;
};

/**
 * @brief Writes a geokiosk store (GeoPackage 1.3 + our extensions) in one transaction.
 *
 * Used by the importer on a private temporary copy of the store, so it trades durability for
 * speed (no journal, no fsync); the importer renames the file into place after commit().
 * Not thread-safe: tiles are encoded on worker threads and handed to one writer thread.
 * Never throws; every error names the file and the table/tile.
 */
class StoreWriter {
public:
    /** @brief Open (`create` = new empty file, else an existing store) and begin a transaction. */
    static Result<std::unique_ptr<StoreWriter>> open(const std::filesystem::path& path,
                                                     bool create);
    ~StoreWriter();

    /** @brief The store's grid once defined (read from kiosk_grid for an existing store). */
    const std::optional<TileGrid>& grid() const noexcept { return mGrid; }
    /** @brief Define the store's one grid and CRS (only once per store). */
    Diagnostics defineGrid(const TileGrid& grid);

    bool hasTable(const std::string& name);
    /** @brief Table name is a plain identifier that can be a GeoPackage table. */
    static bool validTableName(const std::string& name);

    Diagnostics createScalarLayer(const ScalarLayerSpec& spec);
    /** @brief Most pyramid levels an imagery layer may add below the grid's finest. */
    static constexpr int kMaxExtraImageryLevels = 3;
    /**
     * @brief An imagery layer; `extraLevels` > 0 continues its pyramid that many levels finer
     * than the grid (same extent, pixel size halved per level): imagery at its own resolution.
     */
    Diagnostics createImageryLayer(const std::string& table, const std::string& description,
                                   int extraLevels = 0);
    Diagnostics putScalarTile(const std::string& table, const TileId& id,
                              const EncodedScalarTile& tile);
    Diagnostics putImageTile(const std::string& table, const TileId& id,
                             const std::vector<std::uint8_t>& blob);
    /** @brief Record final value range, data extent and tile count of a layer. */
    Diagnostics finishLayer(const std::string& table, double minValue, double maxValue,
                            double dataMinX, double dataMinY, double dataMaxX, double dataMaxY);

    Diagnostics createSequence(const SequenceSpec& spec);
    Diagnostics addSequenceFrame(const std::string& sequence, int index, double epochSeconds,
                                 const std::string& table, double minValue, double maxValue);
    /** @brief Frame times already stored for a sequence (to append in order). */
    std::vector<double> sequenceTimes(const std::string& sequence);
    /** @brief Data extent (min x, min y, max x, max y) recorded for a finished layer. */
    std::optional<std::array<double, 4>> layerDataExtent(const std::string& table);
    /** @brief Units of a sequence already in the store; nullopt when there is no such sequence. */
    std::optional<std::string> sequenceUnits(const std::string& sequence);

    /** @brief Read back a tile written earlier in this transaction (pyramid building). */
    Result<RasterTile> readScalarTile(const std::string& table, const TileId& id);
    Result<ImageTile> readImageTile(const std::string& table, const TileId& id);

    /**
     * @brief Create kiosk_tile_meshes (and register its extension) if the store has none yet;
     * StoreWriterMeshes.cpp. Stores imported without meshes stay without the table.
     */
    Diagnostics createTileMeshes();
    /**
     * @brief Store one tier of a tile's simplified mesh (encodeMeshBlob output); `splitTiers`:
     * the blob has QuantizedMesh::splitTiers (coarser tiers derive from it).
     */
    Diagnostics putTileMesh(const std::string& table, const TileId& id, int tier, double tolerance,
                            std::size_t vertices, std::size_t triangles, bool splitTiers,
                            const std::vector<std::uint8_t>& blob);
    /**
     * @brief Create kiosk_tile_tins (and register its extension) if the store has none yet;
     * StoreWriterTins.cpp.
     */
    Diagnostics createTileTins();
    /** @brief Remove the TINs an earlier import named `source` wrote for `table` (a re-import). */
    Diagnostics deleteTileTins(const std::string& table, const std::string& source);
    /** @brief The source of the TIN a tile has already (nullopt: none). */
    std::optional<std::string> tileTinSource(const std::string& table, const TileId& id);
    /** @brief Store (or replace) a tile's TIN of tolerance tier `tier` (encodeTinBlob output). */
    Diagnostics putTileTin(const std::string& table, const TileId& id, int tier,
                           const std::string& source, double tolerance, double maxError,
                           std::size_t vertices, std::size_t triangles,
                           const std::vector<std::uint8_t>& blob);
    /**
     * @brief Create kiosk_tile_textures (and register its extension) if the store has none yet;
     * StoreWriterTextures.cpp.
     */
    Diagnostics createTileTextures();
    /** @brief Remove a layer's stored textures of `format` (import textures replaces them). */
    Diagnostics deleteTileTextures(const std::string& table, TextureFormat format);
    /** @brief Store (or replace) a tile's GPU blocks; `psnrDb`: level 0 against the PNG. */
    Diagnostics putTileTexture(const std::string& table, const CompressedImage& image,
                               double psnrDb);
    /** @brief Every tile of a table, coarse levels first (for a pass over a finished layer). */
    Result<std::vector<TileId>> tileIds(const std::string& table);

    /** @brief Commit, set GeoPackage header fields, close. The writer is unusable after. */
    Diagnostics commit();

    const std::string& path() const noexcept { return mDb.path(); }

private:
    StoreWriter() = default;
    Diagnostics createSchema();
    Diagnostics loadGrid();
    Diagnostics insertMatrices(const std::string& table, const std::string& dataType,
                               const std::string& description, int extraLevels = 0);
    Diagnostics registerExtension(const std::string& table, const char* column,
                                  const std::string& extension, const std::string& definition);

    SqliteDb mDb;
    std::optional<TileGrid> mGrid;
    std::unique_ptr<TileQueries> mQueries;
    std::map<std::string, Statement> mInsertTile;
    Statement mInsertAncillary, mInsertStats, mInsertMesh, mInsertTin, mInsertTexture;
    std::map<std::string, double> mScaleOf;
    bool mCommitted = false;
};

}  // namespace kiosk::io
