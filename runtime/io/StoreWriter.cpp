#include "runtime/io/StoreWriter.h"

#include <cctype>
#include <cmath>

namespace kiosk::io {

StoreWriter::~StoreWriter() {
    if (!mCommitted && mDb.handle()) mDb.exec("ROLLBACK");
}

Result<std::unique_ptr<StoreWriter>> StoreWriter::open(const std::filesystem::path& path,
                                                       bool create) {
    auto db = SqliteDb::open(path, create ? SqliteDb::Mode::Create : SqliteDb::Mode::ReadWrite);
    if (!db) return db.diagnostics;
    std::unique_ptr<StoreWriter> w(new StoreWriter());
    w->mDb = std::move(*db);
    Diagnostics d;
    // Private temporary file: a crash leaves only a temp file the importer deletes, so no
    // journal and no fsync until the final commit.
    d.append(
        w->mDb.exec("PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF; "
                    "PRAGMA cache_size=-32768; BEGIN"));
    if (d.hasErrors()) return d;
    if (!create && !w->mDb.tableExists(kGridTable)) {
        d.error("STORE_NOT_GEOKIOSK", w->mDb.path(), "",
                "not a geokiosk store (no kiosk_grid table)");
        return d;
    }
    d.append(w->createSchema());
    if (d.hasErrors()) return d;
    d.append(w->loadGrid());
    if (d.hasErrors()) return d;
    w->mQueries = std::make_unique<TileQueries>(w->mDb);
    return Result<std::unique_ptr<StoreWriter>>(std::move(w));
}

Diagnostics StoreWriter::loadGrid() {
    Diagnostics d;
    auto st = mDb.prepare(
        "SELECT g.srs_id, g.min_x, g.min_y, g.max_x, g.max_y, g.tile_width, g.tile_height, "
        "g.levels, g.finest_pixel_size, s.srs_name, s.definition FROM kiosk_grid g LEFT JOIN "
        "gpkg_spatial_ref_sys s ON s.srs_id = g.srs_id WHERE g.id = 1");
    if (!st) return st.diagnostics;
    if (st->step() != SQLITE_ROW) return d;
    TileGrid g;
    g.srsId = int(st->columnInt(0));
    g.minX = st->columnDouble(1);
    g.minY = st->columnDouble(2);
    g.maxX = st->columnDouble(3);
    g.maxY = st->columnDouble(4);
    const int tw = int(st->columnInt(5)), th = int(st->columnInt(6));
    const int levels = int(st->columnInt(7));
    const double finest = st->columnDouble(8);
    g.crsName = st->columnText(9);
    g.crsWkt = st->columnText(10);
    g.setPyramid(levels, tw, th, finest);
    mGrid = g;
    return d;
}

Diagnostics StoreWriter::defineGrid(const TileGrid& grid) {
    Diagnostics d;
    if (mGrid) {
        d.error("STORE_GRID_DEFINED", mDb.path(), kGridTable, "store already has a tile grid");
        return d;
    }
    if (grid.levels.empty()) {
        d.error("STORE_GRID_INVALID", mDb.path(), kGridTable, "grid has no levels");
        return d;
    }
    const bool epsg = grid.srsId > 0 && grid.srsId < 100000;
    auto srs = mDb.prepare("INSERT OR REPLACE INTO gpkg_spatial_ref_sys VALUES (?,?,?,?,?,?)");
    if (!srs) return srs.diagnostics;
    srs->bind(1, std::string_view(grid.crsName.empty() ? "unnamed" : grid.crsName));
    srs->bindInt(2, grid.srsId);
    srs->bind(3, std::string_view(epsg ? "EPSG" : "NONE"));
    srs->bindInt(4, grid.srsId);
    srs->bind(5, std::string_view(grid.crsWkt.empty() ? "undefined" : grid.crsWkt));
    srs->bind(6, std::string_view("geokiosk store CRS"));
    if (srs->step() != SQLITE_DONE) {
        d.add(mDb.error("STORE_SQL", "gpkg_spatial_ref_sys", "cannot insert CRS"));
        return d;
    }
    auto st = mDb.prepare("INSERT INTO kiosk_grid VALUES (1,?,?,?,?,?,?,?,?,?)");
    if (!st) return st.diagnostics;
    const TileMatrix& finest = grid.levels.back();
    st->bindInt(1, grid.srsId);
    st->bind(2, grid.minX);
    st->bind(3, grid.minY);
    st->bind(4, grid.maxX);
    st->bind(5, grid.maxY);
    st->bindInt(6, finest.tileWidth);
    st->bindInt(7, finest.tileHeight);
    st->bindInt(8, int(grid.levels.size()));
    st->bind(9, finest.pixelXSize);
    if (st->step() != SQLITE_DONE) {
        d.add(mDb.error("STORE_SQL", kGridTable, "cannot write grid"));
        return d;
    }
    mGrid = grid;
    return d;
}

bool StoreWriter::hasTable(const std::string& name) {
    return mDb.tableExists(name);
}

bool StoreWriter::validTableName(const std::string& name) {
    if (name.empty() || name.size() > 60) return false;
    if (!(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return false;
    for (char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
    return name.rfind("gpkg_", 0) != 0 && name.rfind("sqlite_", 0) != 0 &&
           name.rfind("kiosk_", 0) != 0;
}

Diagnostics StoreWriter::insertMatrices(const std::string& table, const std::string& dataType,
                                        const std::string& description, int extraLevels) {
    Diagnostics d;
    if (!mGrid) {
        d.error("STORE_NO_GRID", mDb.path(), table, "store has no tile grid yet");
        return d;
    }
    if (!validTableName(table)) {
        d.error("STORE_BAD_NAME", mDb.path(), table,
                "layer name must be letters, digits and '_' (not starting with gpkg_, kiosk_ "
                "or a digit)");
        return d;
    }
    if (mDb.tableExists(table)) {
        d.error("STORE_LAYER_EXISTS", mDb.path(), table, "a layer of that name already exists");
        return d;
    }
    const TileGrid& g = *mGrid;
    d.append(mDb.exec("CREATE TABLE " + quoteIdentifier(table) +
                      " (id INTEGER PRIMARY KEY AUTOINCREMENT, zoom_level INTEGER NOT NULL, "
                      "tile_column INTEGER NOT NULL, tile_row INTEGER NOT NULL, tile_data BLOB "
                      "NOT NULL, UNIQUE (zoom_level, tile_column, tile_row))"));
    if (d.hasErrors()) return d;
    auto c = mDb.prepare(
        "INSERT INTO gpkg_contents (table_name, data_type, identifier, "
        "description, min_x, min_y, max_x, max_y, srs_id) VALUES "
        "(?,?,?,?,?,?,?,?,?)");
    if (!c) return c.diagnostics;
    c->bind(1, std::string_view(table));
    c->bind(2, std::string_view(dataType));
    c->bind(3, std::string_view(table));
    c->bind(4, std::string_view(description));
    c->bind(5, g.minX);
    c->bind(6, g.minY);
    c->bind(7, g.maxX);
    c->bind(8, g.maxY);
    c->bindInt(9, g.srsId);
    if (c->step() != SQLITE_DONE) {
        d.add(mDb.error("STORE_SQL", "gpkg_contents", "cannot add " + table));
        return d;
    }
    auto s = mDb.prepare("INSERT INTO gpkg_tile_matrix_set VALUES (?,?,?,?,?,?)");
    if (!s) return s.diagnostics;
    s->bind(1, std::string_view(table));
    s->bindInt(2, g.srsId);
    s->bind(3, g.minX);
    s->bind(4, g.minY);
    s->bind(5, g.maxX);
    s->bind(6, g.maxY);
    if (s->step() != SQLITE_DONE) {
        d.add(mDb.error("STORE_SQL", "gpkg_tile_matrix_set", "cannot add " + table));
        return d;
    }
    auto m = mDb.prepare("INSERT INTO gpkg_tile_matrix VALUES (?,?,?,?,?,?,?,?)");
    if (!m) return m.diagnostics;
    // Imagery finer than the grid continues its pyramid: the same extent, pixels halved.
    TileGrid own = g;
    own.setPyramid(int(g.levels.size()) + extraLevels, g.levels.back().tileWidth,
                   g.levels.back().tileHeight,
                   g.levels.back().pixelXSize / double(1 << extraLevels));
    for (const TileMatrix& tm : own.levels) {
        m->reset();
        m->bind(1, std::string_view(table));
        m->bindInt(2, tm.level);
        m->bindInt(3, tm.matrixWidth);
        m->bindInt(4, tm.matrixHeight);
        m->bindInt(5, tm.tileWidth);
        m->bindInt(6, tm.tileHeight);
        m->bind(7, tm.pixelXSize);
        m->bind(8, tm.pixelYSize);
        if (m->step() != SQLITE_DONE) {
            d.add(mDb.error("STORE_SQL", "gpkg_tile_matrix", "cannot add " + table));
            return d;
        }
    }
    return d;
}

Diagnostics StoreWriter::createScalarLayer(const ScalarLayerSpec& spec) {
    Diagnostics d = insertMatrices(spec.table, "2d-gridded-coverage", spec.description);
    if (d.hasErrors()) return d;
    // GDAL (3.6) takes a coverage's Min/Max from the tile ancillary rows whose tpudt_id is one of
    // the table's tile ids, whatever their tpudt_name: tile ids start past every id already
    // used by a coverage of this store, so no two coverages share one.
    auto seq = mDb.prepare(
        "INSERT INTO sqlite_sequence (name, seq) SELECT ?, COALESCE(MAX(tpudt_id), 0) FROM "
        "gpkg_2d_gridded_tile_ancillary");
    if (!seq) return seq.diagnostics;
    seq->bind(1, std::string_view(spec.table));
    if (seq->step() != SQLITE_DONE) {
        d.add(mDb.error("STORE_SQL", "sqlite_sequence", spec.table));
        return d;
    }
    auto a = mDb.prepare(
        "INSERT INTO gpkg_2d_gridded_coverage_ancillary (tile_matrix_set_name, "
        "datatype, scale, offset, precision, data_null, uom, field_name, "
        "quantity_definition) VALUES (?, 'integer', 1.0, 0.0, ?, ?, ?, ?, ?)");
    if (!a) return a.diagnostics;
    const bool elevation = spec.kind == LayerKind::Elevation;
    a->bind(1, std::string_view(spec.table));
    a->bind(2, spec.scale);
    a->bind(3, double(kNodataRaw));
    a->bind(4, std::string_view(spec.units));
    a->bind(5, std::string_view(elevation ? "Height" : "Value"));
    a->bind(6, std::string_view(elevation ? "Height" : "Value"));
    if (a->step() != SQLITE_DONE) {
        d.add(mDb.error("STORE_SQL", "gpkg_2d_gridded_coverage_ancillary", spec.table));
        return d;
    }
    d.append(registerExtension(spec.table, "tile_data", kCoverageExtension, kCoverageDefinition));
    auto l = mDb.prepare(
        "INSERT INTO kiosk_layers (table_name, kind, units, nodata, levels, "
        "tile_count, precision, description) VALUES (?,?,?,?,?,0,?,?)");
    if (!l) return l.diagnostics;
    l->bind(1, std::string_view(spec.table));
    l->bind(2, std::string_view(layerKindName(spec.kind)));
    l->bind(3, std::string_view(spec.units));
    if (spec.nodata)
        l->bind(4, *spec.nodata);
    else
        l->bindNull(4);
    l->bindInt(5, int(mGrid->levels.size()));
    l->bind(6, spec.scale);
    l->bind(7, std::string_view(spec.description));
    if (l->step() != SQLITE_DONE) d.add(mDb.error("STORE_SQL", kLayersTable, spec.table));
    mScaleOf[spec.table] = spec.scale;
    return d;
}

Diagnostics StoreWriter::createImageryLayer(const std::string& table,
                                            const std::string& description, int extraLevels) {
    Diagnostics d;
    if (extraLevels < 0 || extraLevels > kMaxExtraImageryLevels) {
        d.error("STORE_BAD_LEVELS", mDb.path(), table,
                "imagery may refine the grid by 0 to " + std::to_string(kMaxExtraImageryLevels) +
                    " levels");
        return d;
    }
    d = insertMatrices(table, "tiles", description, extraLevels);
    if (d.hasErrors()) return d;
    auto l = mDb.prepare(
        "INSERT INTO kiosk_layers (table_name, kind, units, levels, tile_count, "
        "description) VALUES (?, 'imagery', '', ?, 0, ?)");
    if (!l) return l.diagnostics;
    l->bind(1, std::string_view(table));
    l->bindInt(2, int(mGrid->levels.size()) + extraLevels);
    l->bind(3, std::string_view(description));
    if (l->step() != SQLITE_DONE) d.add(mDb.error("STORE_SQL", kLayersTable, table));
    return d;
}

Diagnostics StoreWriter::putImageTile(const std::string& table, const TileId& id,
                                      const std::vector<std::uint8_t>& blob) {
    Diagnostics d;
    auto it = mInsertTile.find(table);
    if (it == mInsertTile.end()) {
        auto st = mDb.prepare("INSERT INTO " + quoteIdentifier(table) +
                              " (zoom_level, tile_column, tile_row, tile_data) VALUES (?,?,?,?)");
        if (!st) return st.diagnostics;
        it = mInsertTile.emplace(table, std::move(*st)).first;
    }
    Statement& st = it->second;
    st.reset();
    st.bindInt(1, id.level);
    st.bindInt(2, id.column);
    st.bindInt(3, id.row);
    st.bindBlob(4, blob.data(), blob.size());
    if (st.step() != SQLITE_DONE)
        d.add(mDb.error("STORE_WRITE", tileName(table, id), "cannot write tile"));
    return d;
}

Diagnostics StoreWriter::putScalarTile(const std::string& table, const TileId& id,
                                       const EncodedScalarTile& tile) {
    Diagnostics d = putImageTile(table, id, tile.png);
    if (d.hasErrors()) return d;
    const std::int64_t rowId = std::int64_t(sqlite3_last_insert_rowid(mDb.handle()));
    if (!mInsertAncillary.valid()) {
        auto st = mDb.prepare(
            "INSERT INTO gpkg_2d_gridded_tile_ancillary (tpudt_name, tpudt_id, "
            "scale, offset, min, max) VALUES (?,?,?,?,?,?)");
        if (!st) return st.diagnostics;
        mInsertAncillary = std::move(*st);
        auto s2 = mDb.prepare("INSERT OR REPLACE INTO kiosk_tile_stats VALUES (?,?,?,?,?,?,?,?)");
        if (!s2) return s2.diagnostics;
        mInsertStats = std::move(*s2);
    }
    mInsertAncillary.reset();
    mInsertAncillary.bind(1, std::string_view(table));
    mInsertAncillary.bind(2, rowId);
    mInsertAncillary.bind(3, tile.scale);
    mInsertAncillary.bind(4, tile.offset);
    mInsertAncillary.bind(5, double(tile.stats.minValue));
    mInsertAncillary.bind(6, double(tile.stats.maxValue));
    if (mInsertAncillary.step() != SQLITE_DONE) {
        d.add(mDb.error("STORE_WRITE", tileName(table, id), "cannot write tile ancillary"));
        return d;
    }
    mInsertStats.reset();
    mInsertStats.bind(1, std::string_view(table));
    mInsertStats.bindInt(2, id.level);
    mInsertStats.bindInt(3, id.column);
    mInsertStats.bindInt(4, id.row);
    mInsertStats.bind(5, double(tile.stats.minValue));
    mInsertStats.bind(6, double(tile.stats.maxValue));
    mInsertStats.bind(7, double(tile.stats.geometricError));
    mInsertStats.bindBlob(8, tile.border.data(), tile.border.size() * sizeof(float));
    if (mInsertStats.step() != SQLITE_DONE)
        d.add(mDb.error("STORE_WRITE", tileName(table, id), "cannot write tile statistics"));
    return d;
}

Diagnostics StoreWriter::finishLayer(const std::string& table, double minValue, double maxValue,
                                     double dataMinX, double dataMinY, double dataMaxX,
                                     double dataMaxY) {
    Diagnostics d;
    auto st = mDb.prepare(
        "UPDATE kiosk_layers SET min_value = ?, max_value = ?, data_min_x = ?, "
        "data_min_y = ?, data_max_x = ?, data_max_y = ?, tile_count = (SELECT "
        "COUNT(*) FROM " +
        quoteIdentifier(table) + ") WHERE table_name = ?");
    if (!st) return st.diagnostics;
    st->bind(1, minValue);
    st->bind(2, maxValue);
    st->bind(3, dataMinX);
    st->bind(4, dataMinY);
    st->bind(5, dataMaxX);
    st->bind(6, dataMaxY);
    st->bind(7, std::string_view(table));
    if (st->step() != SQLITE_DONE) {
        d.add(mDb.error("STORE_SQL", kLayersTable, table));
        return d;
    }
    // GDAL sizes the raster by the contents extent: the data, not the whole tile matrix set.
    auto c = mDb.prepare(
        "UPDATE gpkg_contents SET min_x = ?, min_y = ?, max_x = ?, max_y = ?, "
        "last_change = strftime('%Y-%m-%dT%H:%M:%fZ','now') WHERE table_name = ?");
    if (!c) return c.diagnostics;
    c->bind(1, dataMinX);
    c->bind(2, dataMinY);
    c->bind(3, dataMaxX);
    c->bind(4, dataMaxY);
    c->bind(5, std::string_view(table));
    if (c->step() != SQLITE_DONE) d.add(mDb.error("STORE_SQL", "gpkg_contents", table));
    return d;
}

std::optional<std::array<double, 4>> StoreWriter::layerDataExtent(const std::string& table) {
    auto st = mDb.prepare(
        "SELECT data_min_x, data_min_y, data_max_x, data_max_y FROM kiosk_layers WHERE "
        "table_name = ? AND data_min_x IS NOT NULL");
    if (!st) return std::nullopt;
    st->bind(1, std::string_view(table));
    if (st->step() != SQLITE_ROW) return std::nullopt;
    return std::array<double, 4>{st->columnDouble(0), st->columnDouble(1), st->columnDouble(2),
                                 st->columnDouble(3)};
}

Result<RasterTile> StoreWriter::readScalarTile(const std::string& table, const TileId& id) {
    TileQueries::ScalarMeta meta;
    if (mGrid) {
        meta.tileWidth = mGrid->levels.back().tileWidth;
        meta.tileHeight = mGrid->levels.back().tileHeight;
    }
    return mQueries->readScalar(table, meta, id);
}

Result<ImageTile> StoreWriter::readImageTile(const std::string& table, const TileId& id) {
    return mQueries->readImage(table, id);
}

Diagnostics StoreWriter::commit() {
    Diagnostics d;
    mInsertTile.clear();
    mInsertAncillary = Statement();
    mInsertStats = Statement();
    mInsertMesh = Statement();
    mInsertTexture = Statement();
    mQueries.reset();
    d.append(mDb.exec("PRAGMA application_id = " + std::to_string(kGpkgApplicationId) +
                      "; PRAGMA user_version = " + std::to_string(kGpkgUserVersion) +
                      "; COMMIT; PRAGMA journal_mode=DELETE"));
    if (d.hasErrors()) return d;
    mCommitted = true;
    mDb.close();
    return d;
}

}  // namespace kiosk::io
