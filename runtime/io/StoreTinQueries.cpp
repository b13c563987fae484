// TileQueries' part for kiosk_tile_tins (docs/store-format.md "Local TINs").
#include "runtime/io/StoreTables.h"

namespace kiosk::io {

Result<bool> TileQueries::readTin(const std::string& table, const TileId& id, double tolerance,
                                  TileTinRow& out) {
    Diagnostics d;
    if (!mTin.valid()) {
        // The coarsest TIN within the tolerance; the slack only absorbs a different rounding of
        // the same product (import and loader compute tolerances alike).
        auto st = mDb->prepare(
            "SELECT source, tolerance, tin, tier FROM kiosk_tile_tins WHERE table_name = ?1 AND "
            "zoom_level = ?2 AND tile_column = ?3 AND tile_row = ?4 AND tolerance <= ?5 * (1 + "
            "1e-9) ORDER BY tolerance DESC LIMIT 1");
        if (!st) return st.diagnostics;
        mTin = std::move(*st);
    }
    mTin.reset();
    mTin.bind(1, std::string_view(table));
    mTin.bindInt(2, id.level);
    mTin.bindInt(3, id.column);
    mTin.bindInt(4, id.row);
    mTin.bind(5, tolerance);
    const int rc = mTin.step();
    if (rc == SQLITE_DONE) return false;
    if (rc != SQLITE_ROW) {
        d.add(mDb->error("STORE_TIN_CORRUPT", tileName(table, id), "cannot read the tile's TIN"));
        return d;
    }
    out.source = mTin.columnText(0);
    out.tolerance = mTin.columnDouble(1);
    out.tier = int(mTin.columnInt(3));
    const auto [data, size] = mTin.columnBlob(2);
    Diagnostics m = decodeTinBlob(
        data, size, tileName(table, id) + " tier " + std::to_string(out.tier), out.mesh);
    mTin.reset();
    if (m.hasErrors()) {
        for (Diagnostic e : m.items()) {
            e.file = mDb->path();
            d.add(std::move(e));
        }
        return d;
    }
    if (!(out.tolerance >= 0)) {
        d.error("STORE_TIN_CORRUPT", mDb->path(), tileName(table, id),
                "stored TIN has a negative or missing tolerance");
        return d;
    }
    return true;
}

}  // namespace kiosk::io
