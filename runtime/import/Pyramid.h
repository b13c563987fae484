#pragma once

#include "runtime/core/Result.h"
#include "runtime/core/Progress.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/io/StoreWriter.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace kiosk::import {

/** @brief Pixel window [x0, x1) x [y0, y1) at the grid's finest level, from the grid origin. */
struct GridWindow {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
};

/**
 * @brief Supplies `rows` finest-level rows of the window starting at window row `row0`,
 * `window.width()` values per row (float, NaN = nodata; or RGBA8 for imagery).
 */
using ScalarRowSource = std::function<Diagnostics(int row0, int rows, float* out)>;
using RgbaRowSource = std::function<Diagnostics(int row0, int rows, std::uint8_t* out)>;

struct PyramidOptions {
    std::string table;
    double scale = 0.125;      ///< quantisation step (power of two)
    bool categorical = false;  ///< downsample by mode instead of mean
    int threads = 2;
    int pngLevel = 2;   ///< zlib level: deflate dominates import time, 2 is ~10 % larger than 6
    bool jpeg = false;  ///< imagery: JPEG for opaque tiles
    Progress* progress = nullptr;
    /** @brief Test hook: fail with IMPORT_INJECTED_FAILURE after this many tiles (< 0 = off). */
    std::int64_t failAfterTiles = -1;
    std::string sourceName;  ///< names the file in diagnostics
};

struct PyramidResult {
    double minValue = 0, maxValue = 0;  ///< finest-level value range (scalar)
    std::int64_t tiles = 0;
    bool clamped = false;
};

/** @brief Number of tiles a window may produce over all levels (for progress). */
std::int64_t estimateTiles(const io::TileGrid& grid, const GridWindow& window);

/**
 * @brief Stream a scalar raster into `writer` (table already created): the finest level row strip
 * by row strip from `source`, then every coarser level from the level below read back from the
 * store, so memory stays bounded by a few tile rows whatever the raster size. Posts, border posts
 * and geometric error follow the RasterTile / TileStats contract in StoreTypes.h. Encoding runs on
 * `threads` threads; all SQLite work stays on the calling thread.
 * Errors: IMPORT_ALL_NODATA (nothing to write), IMPORT_NAN / IMPORT_READ from the source,
 * STORE_* from the writer.
 */
Result<PyramidResult> buildScalarPyramid(io::StoreWriter& writer, const io::TileGrid& grid,
                                         const GridWindow& window, const ScalarRowSource& source,
                                         const PyramidOptions& options);

/** @brief Same for RGBA imagery (no borders, no error; transparent tiles are skipped). */
Result<PyramidResult> buildImageryPyramid(io::StoreWriter& writer, const io::TileGrid& grid,
                                          const GridWindow& window, const RgbaRowSource& source,
                                          const PyramidOptions& options);

/**
 * @brief Geometric error of a coarse tile's quantised posts against the surface of the level below
 * (exact max of |S_coarse - S_fine| over the common refinement, NaN skipped). Exposed for tests.
 * `fine` holds (2T+2)^2 values of the finer level starting at pixel (2cT, 2rT); `posts` (T+1)^2.
 */
float surfaceDeviation(const std::vector<float>& posts, const std::vector<float>& fine, int tile);

}  // namespace kiosk::import
