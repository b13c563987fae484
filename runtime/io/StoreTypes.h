#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "runtime/core/TileId.h"

// Plain data exchanged between the store reader (loader thread) and its consumers. No GL, no
// SQLite: terrain/, loader/ and tests use these without linking the store.
namespace kiosk::io {

/** @brief One level of a tile pyramid (a gpkg_tile_matrix row). Level 0 is one tile. */
struct TileMatrix {
    int level = 0;
    int matrixWidth = 1;   ///< tiles across
    int matrixHeight = 1;  ///< tiles down
    int tileWidth = 256;   ///< pixels
    int tileHeight = 256;
    double pixelXSize = 0;  ///< CRS units (metres) per pixel
    double pixelYSize = 0;
};

/** @brief The grid every layer of a store shares (one CRS, one tile matrix set). */
struct TileGrid {
    int srsId = 0;           ///< gpkg_spatial_ref_sys.srs_id (EPSG code where there is one)
    std::string crsName;     ///< e.g. "WGS 84 / UTM zone 10N"
    std::string crsWkt;
    double minX = 0, minY = 0, maxX = 0, maxY = 0;  ///< tile matrix set bounds, CRS units
    std::vector<TileMatrix> levels;                 ///< index == level

    int maxLevel() const { return static_cast<int>(levels.size()) - 1; }
    /**
     * @brief Replace `levels` with a full pyramid: level l is 2^l x 2^l tiles of
     * tileWidth x tileHeight pixels, each pixel finestPixelSize * 2^(levelCount - 1 - l).
     */
    void setPyramid(int levelCount, int tileWidth, int tileHeight, double finestPixelSize) {
        levels.clear();
        for (int l = 0; l < levelCount; ++l) {
            TileMatrix m;
            m.level = l;
            m.matrixWidth = m.matrixHeight = 1 << l;
            m.tileWidth = tileWidth;
            m.tileHeight = tileHeight;
            m.pixelXSize = m.pixelYSize = finestPixelSize * double(1 << (levelCount - 1 - l));
            levels.push_back(m);
        }
    }
    /** @brief CRS bounds of a tile: x grows east, y north; row 0 is the northernmost. */
    void tileBounds(const TileId& id, double& x0, double& y0, double& x1, double& y1) const {
        const TileMatrix& m = levels[std::size_t(id.level)];
        const double w = m.pixelXSize * m.tileWidth, h = m.pixelYSize * m.tileHeight;
        x0 = minX + id.column * w;
        x1 = x0 + w;
        y1 = maxY - id.row * h;
        y0 = y1 - h;
    }
};

enum class LayerKind { Elevation, Imagery, Sequence };

/** @brief A raster layer of the store (elevation, imagery, or a sequence's frames). */
struct LayerInfo {
    std::string name;       ///< table name, e.g. "elevation", "imagery", "flood_depth"
    LayerKind kind = LayerKind::Elevation;
    std::string units;      ///< "m" for elevation and depth, "" for imagery, free text otherwise
    double minValue = 0, maxValue = 0;  ///< over the whole layer (data units)
    std::optional<double> nodata;       ///< in data units, as declared by the source
    int levels = 0;         ///< number of pyramid levels present
    std::int64_t tileCount = 0;
    double precision = 0;   ///< quantisation step of stored values (scalar layers), data units
    /** @brief Data extent (may be smaller than the grid bounds), CRS units. */
    double dataMinX = 0, dataMinY = 0, dataMaxX = 0, dataMaxY = 0;
};

/** @brief A named, time-keyed sequence of rasters (flood depth, fire burn state). */
struct SequenceInfo {
    std::string name;
    std::string units;                ///< "m", "class", ...
    std::string variable;             ///< source variable, e.g. "depth", "burned"
    bool categorical = false;         ///< class data (burn state): never blend values
    std::optional<double> nodata;
    std::vector<double> frameTimes;   ///< UTC epoch seconds, strictly increasing
    std::vector<double> frameMin, frameMax;  ///< per frame, data units
    int levels = 0;
};

struct StoreInfo {
    std::string path;
    TileGrid grid;
    std::vector<LayerInfo> layers;
    std::vector<SequenceInfo> sequences;
    std::int64_t sizeBytes = 0;
    /** @brief This connection's page cache limit as SQLite reports it (PRAGMA cache_size). */
    std::int64_t pageCacheBytes = 0;

    const LayerInfo* findLayer(const std::string& name) const {
        for (const auto& l : layers)
            if (l.name == name) return &l;
        return nullptr;
    }
    const SequenceInfo* findSequence(const std::string& name) const {
        for (const auto& s : sequences)
            if (s.name == name) return &s;
        return nullptr;
    }
};

/** @brief Per-tile statistics kept beside the pyramid (our extension table). */
struct TileStats {
    float minValue = 0;
    float maxValue = 0;
    /**
     * @brief Geometric error in metres: the maximum vertical deviation of this level's surface
     * (bilinear over the posts below) from the full-resolution data inside the tile. 0 at the
     * finest level. An upper bound; the renderer relies on it for its screen-space guarantee.
     */
    float geometricError = 0;
};

/**
 * @brief Scalar raster of one tile (elevation or a sequence frame), decoded to float.
 *
 * Holds (tileWidth + 1) x (tileHeight + 1) *posts*: the tile's own pixel-centre samples plus the
 * first column of the east neighbour, the first row of the south neighbour and the south-east
 * corner (replicated at the grid's east/south edge), so adjacent tiles share their border posts
 * and meshes built from them meet without cracks. Post (0,0) is the centre of the tile's
 * north-west pixel. NaN marks nodata.
 */
struct RasterTile {
    TileId id;
    int postsX = 0;
    int postsY = 0;
    /** @brief Floats per post (4: a derived product's tile, loader/Derivation.h). */
    int channels = 1;
    std::vector<float> values;  ///< row-major, north row first
    TileStats stats;

    float at(int x, int y) const { return values[std::size_t(y) * std::size_t(postsX) + std::size_t(x)]; }
};

/** @brief Colour tile (imagery, hillshade) decoded to 8-bit RGBA, tileWidth x tileHeight. */
struct ImageTile {
    TileId id;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
};

}  // namespace kiosk::io
