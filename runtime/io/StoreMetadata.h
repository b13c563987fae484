#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/io/SqliteDb.h"

// Range checks of every numeric metadata value of the store format (docs/store-format.md
// "Integrity", "Bounds of metadata values"): a NaN stored as text, an infinite extent, a tile
// matrix 1e9 tiles wide or a scale of 1e308 would otherwise be read as a number (0 for text)
// and drawn, or tiled, wrong without a word.
namespace kiosk::io {

/** @brief Largest |coordinate| of an extent, CRS units (metres: 25 times the Earth's girth). */
inline constexpr double kMaxStoreCoordinate = 1e9;
/** @brief Largest pixel size of a tile matrix or the grid's finest pixel, CRS units. */
inline constexpr double kMaxStorePixelSize = 1e7;

/**
 * @brief Check the metadata tables of the store in `db` (schema already checked): kiosk_grid,
 * and for the tables kiosk_layers lists their gpkg_tile_matrix_set, gpkg_tile_matrix,
 * gpkg_2d_gridded_coverage_ancillary, gpkg_2d_gridded_tile_ancillary and kiosk_tile_stats rows,
 * kiosk_layers, kiosk_sequences, kiosk_sequence_frames. One STORE_METADATA error per table,
 * naming the table, the first bad row and its column and the count of further bad rows.
 */
Diagnostics checkStoreMetadata(SqliteDb& db);

}  // namespace kiosk::io
