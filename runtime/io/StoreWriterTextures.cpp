// StoreWriter's part for kiosk_tile_textures (docs/store-format.md): GPU block-compressed copies
// of imagery tiles, written by `geokiosk import textures`.
#include "runtime/io/StoreWriter.h"

namespace kiosk::io {

namespace {

// A rowid table like kiosk_tile_meshes (blobs of kilobytes). The UNIQUE index serves the
// loader's lookup (tile, then format).
constexpr const char* kTextureSchema = R"SQL(
CREATE TABLE IF NOT EXISTS kiosk_tile_textures (id INTEGER PRIMARY KEY, table_name TEXT NOT NULL,
  zoom_level INTEGER NOT NULL, tile_column INTEGER NOT NULL, tile_row INTEGER NOT NULL,
  format TEXT NOT NULL, width INTEGER NOT NULL, height INTEGER NOT NULL, levels INTEGER NOT NULL,
  psnr_db DOUBLE NOT NULL, blocks BLOB NOT NULL,
  UNIQUE (table_name, zoom_level, tile_column, tile_row, format));
)SQL";

}  // namespace

Diagnostics StoreWriter::createTileTextures() {
    Diagnostics d = mDb.exec(kTextureSchema);
    if (d.hasErrors()) return d;
    d.append(registerExtension(kTileTexturesTable, nullptr, kTileTexturesExtension,
                               std::string(kOurDefinition) + "#kiosk_tile_textures"));
    return d;
}

Diagnostics StoreWriter::deleteTileTextures(const std::string& table, TextureFormat format) {
    auto st = mDb.prepare("DELETE FROM kiosk_tile_textures WHERE table_name = ? AND format = ?");
    if (!st) return st.diagnostics;
    st->bind(1, std::string_view(table));
    st->bind(2, std::string_view(textureFormatName(format)));
    Diagnostics d;
    if (st->step() != SQLITE_DONE)
        d.add(mDb.error("STORE_WRITE", table, "cannot remove stored textures"));
    return d;
}

Diagnostics StoreWriter::putTileTexture(const std::string& table, const CompressedImage& image,
                                        double psnrDb) {
    Diagnostics d;
    if (!mInsertTexture.valid()) {
        auto st = mDb.prepare(
            "INSERT OR REPLACE INTO kiosk_tile_textures (table_name, zoom_level, tile_column, "
            "tile_row, format, width, height, levels, psnr_db, blocks) VALUES "
            "(?,?,?,?,?,?,?,?,?,?)");
        if (!st) return st.diagnostics;
        mInsertTexture = std::move(*st);
    }
    Statement& st = mInsertTexture;
    st.reset();
    st.bind(1, std::string_view(table));
    st.bindInt(2, image.id.level);
    st.bindInt(3, image.id.column);
    st.bindInt(4, image.id.row);
    st.bind(5, std::string_view(textureFormatName(image.format)));
    st.bindInt(6, image.width);
    st.bindInt(7, image.height);
    st.bindInt(8, image.levels);
    st.bind(9, psnrDb);
    st.bindBlob(10, image.blocks.data(), image.blocks.size());
    if (st.step() != SQLITE_DONE)
        d.add(mDb.error("STORE_WRITE", tileName(table, image.id), "cannot write stored texture"));
    return d;
}

}  // namespace kiosk::io
