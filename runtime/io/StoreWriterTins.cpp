// StoreWriter's part for kiosk_tile_tins (docs/store-format.md "Local TINs").
#include "runtime/io/StoreWriter.h"

namespace kiosk::io {

namespace {

// One TIN per elevation tile and tolerance tier: a later import over the same tile replaces it
// (the importer warns when that TIN came from another source).
constexpr const char* kTinSchema = R"SQL(
CREATE TABLE IF NOT EXISTS kiosk_tile_tins (id INTEGER PRIMARY KEY, table_name TEXT NOT NULL,
  zoom_level INTEGER NOT NULL, tile_column INTEGER NOT NULL, tile_row INTEGER NOT NULL,
  tier INTEGER NOT NULL, source TEXT NOT NULL, tolerance DOUBLE NOT NULL,
  max_error DOUBLE NOT NULL, vertex_count INTEGER NOT NULL, triangle_count INTEGER NOT NULL,
  tin BLOB NOT NULL, UNIQUE (table_name, zoom_level, tile_column, tile_row, tier));
)SQL";

}  // namespace

Diagnostics StoreWriter::createTileTins() {
    Diagnostics d = mDb.exec(kTinSchema);
    if (d.hasErrors()) return d;
    d.append(registerExtension(kTileTinsTable, nullptr, kTileTinsExtension,
                               std::string(kOurDefinition) + "#kiosk_tile_tins"));
    return d;
}

Diagnostics StoreWriter::deleteTileTins(const std::string& table, const std::string& source) {
    Diagnostics d;
    auto st = mDb.prepare("DELETE FROM kiosk_tile_tins WHERE table_name = ? AND source = ?");
    if (!st) return st.diagnostics;
    st->bind(1, std::string_view(table));
    st->bind(2, std::string_view(source));
    if (st->step() != SQLITE_DONE)
        d.add(mDb.error("STORE_WRITE", table, "cannot remove the TINs of '" + source + "'"));
    return d;
}

std::optional<std::string> StoreWriter::tileTinSource(const std::string& table, const TileId& id) {
    auto st = mDb.prepare(
        "SELECT source FROM kiosk_tile_tins WHERE table_name = ? AND zoom_level = ? AND "
        "tile_column = ? AND tile_row = ? LIMIT 1");
    if (!st) return std::nullopt;
    st->bind(1, std::string_view(table));
    st->bindInt(2, id.level);
    st->bindInt(3, id.column);
    st->bindInt(4, id.row);
    if (st->step() != SQLITE_ROW) return std::nullopt;
    return st->columnText(0);
}

Diagnostics StoreWriter::putTileTin(const std::string& table, const TileId& id, int tier,
                                    const std::string& source, double tolerance, double maxError,
                                    std::size_t vertices, std::size_t triangles,
                                    const std::vector<std::uint8_t>& blob) {
    Diagnostics d;
    if (!mInsertTin.valid()) {
        auto st = mDb.prepare(
            "INSERT OR REPLACE INTO kiosk_tile_tins (table_name, zoom_level, tile_column, "
            "tile_row, tier, source, tolerance, max_error, vertex_count, triangle_count, tin) "
            "VALUES (?,?,?,?,?,?,?,?,?,?,?)");
        if (!st) return st.diagnostics;
        mInsertTin = std::move(*st);
    }
    Statement& st = mInsertTin;
    st.reset();
    st.bind(1, std::string_view(table));
    st.bindInt(2, id.level);
    st.bindInt(3, id.column);
    st.bindInt(4, id.row);
    st.bindInt(5, tier);
    st.bind(6, std::string_view(source));
    st.bind(7, tolerance);
    st.bind(8, maxError);
    st.bind(9, std::int64_t(vertices));
    st.bind(10, std::int64_t(triangles));
    st.bindBlob(11, blob.data(), blob.size());
    if (st.step() != SQLITE_DONE)
        d.add(mDb.error("STORE_WRITE", tileName(table, id) + " tier " + std::to_string(tier),
                        "cannot write the tile's TIN"));
    return d;
}

}  // namespace kiosk::io
