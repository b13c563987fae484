#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/core/Progress.h"
#include "runtime/io/StoreWriter.h"

#include <string>

namespace kiosk::import {

/** @brief What storeTileMeshes wrote. */
struct TileMeshStats {
    std::int64_t tiles = 0;      ///< tiles with stored meshes
    std::int64_t rows = 0;       ///< mesh rows (one per tile, more for tiles with nodata)
    std::int64_t skipped = 0;    ///< tiles left to be meshed on load (heights not quantisable)
    std::int64_t blobBytes = 0;  ///< compressed bytes over all rows
};

/**
 * @brief Preprocess an elevation layer whose pyramid is written (Wahl et al. 2004, sections 3-4):
 * every tile is simplified as the loader would simplify it (RTIN with the default
 * TerrainOptions' tolerance of its stored error) and its surface is kept compressed in
 * kiosk_tile_meshes: tier 0 with each vertex's split tier, from which the loader derives every
 * coarser tolerance tier; tiles with nodata (where that does not hold) keep tier 0 and each
 * coarser tier with at most half of tier 0's vertices whole, meshed from the posts as the loader
 * would mesh them. The loader then decodes instead of meshing whenever it asks for one of these
 * tolerances (a run with other TerrainOptions meshes on load as before). Tiles are read from the
 * store (the posts exactly as the loader decodes them) on the calling thread, meshed and
 * compressed on `threads` threads.
 */
Result<TileMeshStats> storeTileMeshes(io::StoreWriter& writer, const std::string& table,
                                      double zStep, int threads, Progress& progress);

}  // namespace kiosk::import
