#pragma once

#include "runtime/core/Result.h"
#include "runtime/io/StoreTypes.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kiosk::io {

/** @brief Raw 16-bit value that marks nodata in scalar tiles (gpkg data_null). */
constexpr std::uint16_t kNodataRaw = 65535;
/** @brief Largest raw value carrying data. */
constexpr double kMaxRaw = 65534.0;

/**
 * @brief A scalar tile ready for the store: a 16-bit PNG of the tile's own pixels with its
 * gpkg_2d_gridded_tile_ancillary scale/offset (value = raw * scale + offset), and the border
 * posts (east column incl. the SE corner, then the south row) as float32 for kiosk_tile_stats.
 */
struct EncodedScalarTile {
    std::vector<std::uint8_t> png;
    double scale = 1.0;
    double offset = 0.0;
    std::vector<float> border;  ///< (tileHeight + 1) + tileWidth values, NaN = nodata
    TileStats stats;
    bool clamped = false;  ///< some value did not fit 16 bits at this scale (clamped)
};

/**
 * @brief Quantise posts in place to multiples of `scale` (a power of two), so every tile that
 * holds the same sample decodes it to the same float: adjacent tiles' shared posts are identical.
 * NaN stays NaN. Returns false if the tile holds no value at all.
 */
bool quantizePosts(std::vector<float>& posts, double scale);

/**
 * @brief Encode (tileWidth + 1) x (tileHeight + 1) quantised posts. min/max of stats are set from
 * the posts; geometricError is left for the caller. Thread-safe.
 */
Result<EncodedScalarTile> encodeScalarTile(const std::vector<float>& posts, int tileWidth,
                                           int tileHeight, double scale, int pngLevel);

/**
 * @brief Rebuild posts from a stored tile. `border` may be empty (posts then replicate the
 * tile's last column/row). Errors (IMAGE_DECODE, STORE_TILE_CORRUPT) name `where`.
 */
Result<RasterTile> decodeScalarTile(const std::uint8_t* png, std::size_t pngSize,
                                    const std::uint8_t* border, std::size_t borderSize,
                                    double scale, double offset, double dataNull, int tileWidth,
                                    int tileHeight, const std::string& where);

}  // namespace kiosk::io
