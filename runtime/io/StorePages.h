#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/io/SqliteDb.h"

// Whether every page of a store can be read: the part of `--deep` below the tiles' formats.
// A zeroed page inside a tile table or a blob's overflow chain is invisible to queries that do
// not touch it, so the checks of the tables above it can all pass.
namespace kiosk::io {

/**
 * @brief SQLite's PRAGMA quick_check (b-tree structure, every page reachable once, records
 * well-formed; the b-trees named by their tables), then every row of every table read with
 * all its columns (text and blobs through their overflow pages). STORE_CORRUPT errors: one
 * line for quick_check's findings (the first and a count), one per table that cannot be read
 * to its end (the row where reading stopped and SQLite's message).
 */
Diagnostics checkStorePages(SqliteDb& db);

}  // namespace kiosk::io
