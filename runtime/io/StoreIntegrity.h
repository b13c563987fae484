#pragma once

#include "runtime/core/Diagnostics.h"

#include <filesystem>

// Does a store hold what docs/store-format.md promises? `StoreReader::open` reads only the
// metadata it needs to play; this walks the GeoPackage core tables and every geokiosk table so
// that `validate` and `info --check` notice a store corrupted by hand or by a crash, and with
// `deep` decodes every tile (`info --check --deep`, `validate --deep`).
namespace kiosk::io {

/** @brief Messages past this many tile problems are summed up in one line. */
inline constexpr int kMaxReportedTileProblems = 10;

/** @brief How far to look. */
enum class IntegrityLevel {
    Core,    ///< per table only (CRS, contents, tile matrix, frames): cheap, `render` and `play`
    Tables,  ///< and every tile's ancillary and stats rows, tile counts: `validate`, `info --check`
    Deep,    ///< and every tile's header and pixels decoded: `--deep`
};

/**
 * @brief Check the store at `path` (which StoreReader::open accepted). Errors name the file and
 * the table (or tile, `table/level/column/row`): STORE_INTEGRITY (a core or geokiosk table is
 * missing, empty or inconsistent with another; one line per kind of problem, listing the
 * tables), STORE_TILE_CORRUPT / STORE_TILE_FORMAT / STORE_TILE_SIZE (Deep: a tile that does not
 * decode to what its table holds). Read-only, never throws; memory is one tile at a time.
 */
Diagnostics checkStoreIntegrity(const std::filesystem::path& path, IntegrityLevel level);

}  // namespace kiosk::io
