// StoreWriter's part for kiosk_tile_meshes (docs/store-format.md), apart from the pyramid
// writing in StoreWriter.cpp.
#include "runtime/io/StoreWriter.h"

namespace kiosk::io {

namespace {

// A rowid table, not WITHOUT ROWID: mesh blobs are kilobytes, larger than SQLite advises for
// WITHOUT ROWID rows. The UNIQUE index serves the loader's lookup (tile, then tolerance).
constexpr const char* kMeshSchema = R"SQL(
CREATE TABLE IF NOT EXISTS kiosk_tile_meshes (id INTEGER PRIMARY KEY, table_name TEXT NOT NULL,
  zoom_level INTEGER NOT NULL, tile_column INTEGER NOT NULL, tile_row INTEGER NOT NULL,
  tier INTEGER NOT NULL, tolerance DOUBLE NOT NULL, vertex_count INTEGER NOT NULL,
  triangle_count INTEGER NOT NULL, split_tiers INTEGER NOT NULL, mesh BLOB NOT NULL,
  UNIQUE (table_name, zoom_level, tile_column, tile_row, tier));
)SQL";

}  // namespace

Diagnostics StoreWriter::createTileMeshes() {
    Diagnostics d = mDb.exec(kMeshSchema);
    if (d.hasErrors()) return d;
    d.append(registerExtension(kTileMeshesTable, nullptr, kTileMeshesExtension,
                               std::string(kOurDefinition) + "#kiosk_tile_meshes"));
    return d;
}

Diagnostics StoreWriter::putTileMesh(const std::string& table, const TileId& id, int tier,
                                     double tolerance, std::size_t vertices, std::size_t triangles,
                                     bool splitTiers, const std::vector<std::uint8_t>& blob) {
    Diagnostics d;
    if (!mInsertMesh.valid()) {
        auto st = mDb.prepare(
            "INSERT OR REPLACE INTO kiosk_tile_meshes (table_name, zoom_level, tile_column, "
            "tile_row, tier, tolerance, vertex_count, triangle_count, split_tiers, mesh) VALUES "
            "(?,?,?,?,?,?,?,?,?,?)");
        if (!st) return st.diagnostics;
        mInsertMesh = std::move(*st);
    }
    Statement& st = mInsertMesh;
    st.reset();
    st.bind(1, std::string_view(table));
    st.bindInt(2, id.level);
    st.bindInt(3, id.column);
    st.bindInt(4, id.row);
    st.bindInt(5, tier);
    st.bind(6, tolerance);
    st.bind(7, std::int64_t(vertices));
    st.bind(8, std::int64_t(triangles));
    st.bindInt(9, splitTiers ? 1 : 0);
    st.bindBlob(10, blob.data(), blob.size());
    if (st.step() != SQLITE_DONE)
        d.add(mDb.error("STORE_WRITE", tileName(table, id) + " tier " + std::to_string(tier),
                        "cannot write stored mesh"));
    return d;
}

Result<std::vector<TileId>> StoreWriter::tileIds(const std::string& table) {
    auto st = mDb.prepare("SELECT zoom_level, tile_column, tile_row FROM " +
                          quoteIdentifier(table) + " ORDER BY zoom_level, tile_row, tile_column");
    if (!st) return st.diagnostics;
    std::vector<TileId> ids;
    while (st->step() == SQLITE_ROW)
        ids.push_back(TileId{int(st->columnInt(0)), int(st->columnInt(1)), int(st->columnInt(2))});
    return ids;
}

}  // namespace kiosk::io
