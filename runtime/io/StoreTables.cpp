#include "runtime/io/StoreTables.h"

#include "runtime/io/ImageCodec.h"
#include "runtime/io/ImageHeader.h"
#include "runtime/io/ScalarTileCodec.h"

#include <cmath>
#include <cstdio>

namespace kiosk::io {

namespace {
// Bounds of gpkg_2d_gridded_tile_ancillary scale/offset (value = raw * scale + offset): far
// beyond any terrain or model output in any unit, far below where floats lose all meaning.
constexpr double kMaxTileScale = 1e6;
constexpr double kMaxTileOffset = 1e9;
}  // namespace

const char* layerKindName(LayerKind kind) noexcept {
    switch (kind) {
        case LayerKind::Elevation:
            return "elevation";
        case LayerKind::Imagery:
            return "imagery";
        case LayerKind::Sequence:
            return "sequence_frame";
    }
    return "elevation";
}

std::optional<LayerKind> parseLayerKind(const std::string& name) noexcept {
    if (name == "elevation") return LayerKind::Elevation;
    if (name == "imagery") return LayerKind::Imagery;
    if (name == "sequence_frame") return LayerKind::Sequence;
    return std::nullopt;
}

std::string tileName(const std::string& table, const TileId& id) {
    return table + "/" + std::to_string(id.level) + "/" + std::to_string(id.column) + "/" +
           std::to_string(id.row);
}

Statement* TileQueries::statement(std::map<std::string, Statement>& cache, const std::string& key,
                                  const std::string& sql, Diagnostics& d) {
    auto it = cache.find(key);
    if (it != cache.end()) {
        it->second.reset();
        return &it->second;
    }
    auto st = mDb->prepare(sql);
    if (!st) {
        d.append(st.diagnostics);
        return nullptr;
    }
    return &cache.emplace(key, std::move(*st)).first->second;
}

Result<RasterTile> TileQueries::readScalar(const std::string& table, const ScalarMeta& meta,
                                           const TileId& id) {
    Diagnostics d;
    const std::string where = tileName(table, id);
    Statement* st = statement(
        mScalar, table,
        "SELECT t.tile_data, a.scale, a.offset, s.border_posts, s.min_value, s.max_value, "
        "s.geometric_error, a.tpudt_id IS NULL, s.table_name IS NULL, typeof(a.scale) IN "
        "('integer', 'real') AND typeof(a.offset) IN ('integer', 'real'), typeof(s.min_value) "
        "IN ('integer', 'real') AND typeof(s.max_value) IN ('integer', 'real') AND "
        "typeof(s.geometric_error) IN ('integer', 'real') FROM " +
            quoteIdentifier(table) +
            " t LEFT JOIN gpkg_2d_gridded_tile_ancillary a ON a.tpudt_name = ?1 AND "
            "a.tpudt_id = t.id LEFT JOIN kiosk_tile_stats s ON s.table_name = ?1 AND "
            "s.zoom_level = t.zoom_level AND s.tile_column = t.tile_column AND "
            "s.tile_row = t.tile_row WHERE t.zoom_level = ?2 AND t.tile_column = ?3 AND "
            "t.tile_row = ?4",
        d);
    if (!st) {
        d.error("STORE_TILE_CORRUPT", mDb->path(), where, "cannot query tile table");
        return d;
    }
    st->bind(1, std::string_view(table));
    st->bindInt(2, id.level);
    st->bindInt(3, id.column);
    st->bindInt(4, id.row);
    const int rc = st->step();
    if (rc != SQLITE_ROW) {
        if (rc == SQLITE_DONE)
            d.error("STORE_TILE_MISSING", mDb->path(), where, "tile not in store");
        else
            d.add(mDb->error("STORE_TILE_CORRUPT", where, "cannot read tile"));
        return d;
    }
    // Without its ancillary row a tile's raw values would be drawn as metres (spikes); without
    // its stats row the selector has no bounds or error for it and the borders are guessed.
    const char* missingRow = st->columnInt(7) != 0   ? "gpkg_2d_gridded_tile_ancillary"
                             : st->columnInt(8) != 0 ? "kiosk_tile_stats"
                                                     : nullptr;
    if (missingRow) {
        d.error("STORE_TILE_CORRUPT", mDb->path(), where,
                std::string("tile has no ") + missingRow + " row");
        st->reset();
        return d;
    }
    // Text such as 'NaN' reads as 0: a flat tile, or bounds that cull it, drawn as data.
    const char* notNumbers = st->columnInt(9) == 0 ? "gpkg_2d_gridded_tile_ancillary scale/offset"
                             : st->columnInt(10) == 0 || !std::isfinite(st->columnDouble(4)) ||
                                     !std::isfinite(st->columnDouble(5)) ||
                                     !std::isfinite(st->columnDouble(6))
                                 ? "kiosk_tile_stats min/max/geometric_error"
                                 : nullptr;
    if (notNumbers) {
        d.error("STORE_TILE_CORRUPT", mDb->path(), where,
                std::string("tile's ") + notNumbers + " are not finite numbers");
        st->reset();
        return d;
    }
    const auto [png, pngSize] = st->columnBlob(0);
    const double scale = st->columnIsNull(1) ? 1.0 : st->columnDouble(1);
    const double offset = st->columnIsNull(2) ? 0.0 : st->columnDouble(2);
    // 16-bit raw values times the scale must stay finite floats with some precision left.
    if (!(scale > 0 && scale <= kMaxTileScale) || !(std::abs(offset) <= kMaxTileOffset)) {
        char text[96];
        std::snprintf(text, sizeof text, "tile scale %g / offset %g", scale, offset);
        d.error("STORE_TILE_CORRUPT", mDb->path(), where,
                std::string(text) + " out of range (scale in (0, 1e6], |offset| <= 1e9)");
        st->reset();
        return d;
    }
    const auto [border, borderSize] = st->columnBlob(3);
    auto tile = decodeScalarTile(png, pngSize, border, borderSize, scale, offset, meta.dataNull,
                                 meta.tileWidth, meta.tileHeight, where);
    if (!tile) {
        for (const auto& item : tile.diagnostics.items()) {
            Diagnostic c = item;
            c.file = mDb->path();
            if (c.code == "IMAGE_DECODE") c.code = "STORE_TILE_CORRUPT";
            d.add(c);
        }
        return d;
    }
    if (meta.coverageScale != 1.0 || meta.coverageOffset != 0.0)
        for (float& v : tile->values) v = float(v * meta.coverageScale + meta.coverageOffset);
    tile->id = id;
    if (!st->columnIsNull(4)) {
        tile->stats.minValue = float(st->columnDouble(4));
        tile->stats.maxValue = float(st->columnDouble(5));
        tile->stats.geometricError = float(st->columnDouble(6));
    }
    st->reset();
    return tile;
}

Result<ImageTile> TileQueries::readImage(const std::string& table, const TileId& id, bool rgb) {
    Diagnostics d;
    const std::string where = tileName(table, id);
    // The tile matrix says what size this level's tiles are: checked before decoding.
    Statement* st =
        statement(mImage, table,
                  "SELECT t.tile_data, m.tile_width, m.tile_height FROM " + quoteIdentifier(table) +
                      " t LEFT JOIN gpkg_tile_matrix m ON m.table_name = ?4 AND "
                      "m.zoom_level = t.zoom_level WHERE t.zoom_level = ?1 AND "
                      "t.tile_column = ?2 AND t.tile_row = ?3",
                  d);
    if (!st) {
        d.error("STORE_TILE_CORRUPT", mDb->path(), where, "cannot query tile table");
        return d;
    }
    st->bindInt(1, id.level);
    st->bindInt(2, id.column);
    st->bindInt(3, id.row);
    st->bind(4, std::string_view(table));
    const int rc = st->step();
    if (rc != SQLITE_ROW) {
        if (rc == SQLITE_DONE)
            d.error("STORE_TILE_MISSING", mDb->path(), where, "tile not in store");
        else
            d.add(mDb->error("STORE_TILE_CORRUPT", where, "cannot read tile"));
        return d;
    }
    const auto [data, size] = st->columnBlob(0);
    if (st->columnIsNull(1)) {
        d.error("STORE_TILE_CORRUPT", mDb->path(), where,
                "no gpkg_tile_matrix row for level " + std::to_string(id.level));
        st->reset();
        return d;
    }
    const TileExpectation expect{int(st->columnInt(1)), int(st->columnInt(2)), false, rgb};
    const Diagnostics header = checkTileHeader(data, size, expect, where);
    for (Diagnostic e : header.items()) {
        e.file = mDb->path();
        d.add(std::move(e));
    }
    if (d.hasErrors()) {
        st->reset();
        return d;
    }
    auto img = decodeRgba8(data, size, where);
    st->reset();
    if (!img) {
        d.error("STORE_TILE_CORRUPT", mDb->path(), where,
                img.diagnostics.firstError() ? img.diagnostics.firstError()->message
                                             : "cannot decode tile");
        return d;
    }
    ImageTile t;
    t.id = id;
    t.width = img->width;
    t.height = img->height;
    t.rgba = std::move(img->samples8);
    return t;
}

Result<bool> TileQueries::readMesh(const std::string& table, const TileId& id, double tolerance,
                                   double baseTolerance, TileMeshRow& out) {
    Diagnostics d;
    if (!mMesh.valid()) {
        // Tolerances are computed the same way at import and here: the slack only absorbs a
        // different rounding of the same product. The exact tolerance first, then tier 0.
        auto st = mDb->prepare(
            "SELECT tier, tolerance, mesh FROM kiosk_tile_meshes WHERE table_name = ?1 AND "
            "zoom_level = ?2 AND tile_column = ?3 AND tile_row = ?4 AND (abs(tolerance - ?5) <= "
            "1e-12 * ?5 OR (tier = 0 AND split_tiers = 1 AND abs(tolerance - ?6) <= 1e-12 * ?6)) "
            "ORDER BY "
            "abs(tolerance - ?5) LIMIT 1");
        if (!st) return st.diagnostics;
        mMesh = std::move(*st);
    }
    mMesh.reset();
    mMesh.bind(1, std::string_view(table));
    mMesh.bindInt(2, id.level);
    mMesh.bindInt(3, id.column);
    mMesh.bindInt(4, id.row);
    mMesh.bind(5, tolerance);
    mMesh.bind(6, baseTolerance);
    const int rc = mMesh.step();
    if (rc == SQLITE_DONE) return false;
    if (rc != SQLITE_ROW) {
        d.add(mDb->error("STORE_MESH_CORRUPT", tileName(table, id), "cannot read stored mesh"));
        return d;
    }
    out.tier = int(mMesh.columnInt(0));
    out.tolerance = mMesh.columnDouble(1);
    const auto [data, size] = mMesh.columnBlob(2);
    Diagnostics m = decodeMeshBlob(
        data, size, tileName(table, id) + " tier " + std::to_string(out.tier), out.mesh);
    mMesh.reset();
    if (m.hasErrors()) {
        for (Diagnostic e : m.items()) {
            e.file = mDb->path();
            d.add(std::move(e));
        }
        return d;
    }
    return true;
}

std::optional<TileStats> TileQueries::stats(const std::string& table, const TileId& id) {
    if (!mStats.valid()) {
        auto st = mDb->prepare(
            "SELECT min_value, max_value, geometric_error FROM kiosk_tile_stats WHERE "
            "table_name = ?1 AND zoom_level = ?2 AND tile_column = ?3 AND tile_row = ?4");
        if (!st) return std::nullopt;
        mStats = std::move(*st);
    }
    mStats.reset();
    mStats.bind(1, std::string_view(table));
    mStats.bindInt(2, id.level);
    mStats.bindInt(3, id.column);
    mStats.bindInt(4, id.row);
    if (mStats.step() != SQLITE_ROW) return std::nullopt;
    TileStats s;
    s.minValue = float(mStats.columnDouble(0));
    s.maxValue = float(mStats.columnDouble(1));
    s.geometricError = float(mStats.columnDouble(2));
    mStats.reset();
    return s;
}

}  // namespace kiosk::io
