#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/io/SqliteDb.h"

// The columns every table of the store format must have (docs/store-format.md "Integrity"), so
// that a renamed or retyped column is one line before any tile is read, not a "no such column"
// per tile query or a picture drawn from defaults.
namespace kiosk::io {

/**
 * @brief Compare every table the format uses that exists in `db` (core GeoPackage tables,
 * geokiosk's, and each tile table listed in kiosk_layers / kiosk_sequence_frames) with its
 * expected columns and their type affinity. Extra columns are allowed. The first drift found is
 * one STORE_SCHEMA error naming the table and the column; missing tables are left to the
 * checks that know whether they are needed.
 */
Diagnostics checkStoreSchema(SqliteDb& db);

}  // namespace kiosk::io
