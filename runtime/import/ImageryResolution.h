#pragma once

#include "runtime/io/StoreTypes.h"

#include <gdal.h>

#include <cstdint>
#include <optional>
#include <string>

// Imagery keeps its own resolution: an orthophoto finer than the store's elevation grid gets
// pyramid levels below the grid's finest (same tile matrix set, pixel size halved per level),
// which the renderer selects by tauTex independently of the geometry level.
namespace kiosk::import {

/**
 * @brief How many levels finer than `grid` imagery from `src` needs so its pixels are not
 * coarsened: the largest k <= `maxExtra` with grid finest pixel / 2^k >= the source's pixel size
 * in the grid's CRS (as GDAL would warp it), reduced while the finest row strip of the source's
 * extent would exceed `budget` (estimateImportBytes). 0 when the source is not finer, or cannot be
 * measured. `assignWkt`: the source's CRS given by --assign-crs (none: its own, or the grid's).
 */
int imageryExtraLevels(GDALDatasetH src, const io::TileGrid& grid, int maxExtra,
                       std::int64_t budget, const std::optional<std::string>& assignWkt);

/** @brief `grid` with `extra` more levels: the same extent, finest pixel halved `extra` times. */
io::TileGrid refinedGrid(const io::TileGrid& grid, int extra);

}  // namespace kiosk::import
