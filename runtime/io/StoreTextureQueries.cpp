// TileQueries' part for kiosk_tile_textures (docs/store-format.md "GPU textures").
#include "runtime/io/StoreTables.h"

namespace kiosk::io {

Result<bool> TileQueries::readTexture(const std::string& table, const TileId& id,
                                      TextureFormat format, CompressedImage& out) {
    Diagnostics d;
    if (!mTexture.valid()) {
        auto st = mDb->prepare(
            "SELECT width, height, levels, blocks FROM kiosk_tile_textures WHERE table_name = ?1 "
            "AND zoom_level = ?2 AND tile_column = ?3 AND tile_row = ?4 AND format = ?5");
        if (!st) return st.diagnostics;
        mTexture = std::move(*st);
    }
    mTexture.reset();
    mTexture.bind(1, std::string_view(table));
    mTexture.bindInt(2, id.level);
    mTexture.bindInt(3, id.column);
    mTexture.bindInt(4, id.row);
    mTexture.bind(5, std::string_view(textureFormatName(format)));
    const int rc = mTexture.step();
    if (rc == SQLITE_DONE) return false;
    if (rc != SQLITE_ROW) {
        d.add(mDb->error("STORE_TEXTURE_CORRUPT", tileName(table, id),
                         "cannot read the tile's stored texture"));
        return d;
    }
    out.id = id;
    out.format = format;
    out.width = int(mTexture.columnInt(0));
    out.height = int(mTexture.columnInt(1));
    out.levels = int(mTexture.columnInt(2));
    const auto [data, size] = mTexture.columnBlob(3);
    // The sizes are checked before the blob is copied: a damaged row never allocates more than
    // the blob it has.
    out.blocks.clear();
    Diagnostics m = checkCompressedImage(out, size, mDb->path(), tileName(table, id));
    if (!m.hasErrors()) out.blocks.assign(data, data + size);
    mTexture.reset();
    if (m.hasErrors()) return m;
    return true;
}

}  // namespace kiosk::io
