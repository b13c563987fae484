#include "runtime/io/StoreIntegrity.h"

#include "runtime/io/ImageCodec.h"
#include "runtime/io/ImageHeader.h"
#include "runtime/io/MeshBlob.h"
#include "runtime/io/ScalarTileCodec.h"
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreMetadata.h"
#include "runtime/io/StorePages.h"
#include "runtime/io/StoreTables.h"
#include "runtime/io/StoreWriter.h"
#include "runtime/io/TinBlob.h"

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace kiosk::io {

namespace {

struct TileTable {
    std::string name;
    bool scalar = false;  // coverage (elevation, sequence frame) vs imagery
    bool rgb = false;     // imagery declared RGB (a normal map)
    int levels = 0;
    std::int64_t tileCount = 0;
};

class Checker {
public:
    Checker(SqliteDb& db, Diagnostics& d) : mDb(db), mD(d) {}

    void run(IntegrityLevel level) {
        for (const char* t : {"gpkg_spatial_ref_sys", "gpkg_contents", "gpkg_tile_matrix_set",
                              "gpkg_tile_matrix", kGridTable, kLayersTable, kTileStatsTable}) {
            if (!mDb.tableExists(t)) error(t, "table is missing");
        }
        if (mD.hasErrors()) return;
        // Unreadable pages first: what the checks below report of them would only follow.
        if (level == IntegrityLevel::Deep) {
            mD.append(checkStorePages(mDb));
            if (mD.hasErrors()) return;
        }
        // A value out of its bounds explains what the checks below would find: said alone.
        mD.append(checkStoreMetadata(mDb));
        if (mD.hasErrors()) return;
        if (!grid()) return;
        layers();
        sequences();
        for (const auto& t : mTables) table(t, level != IntegrityLevel::Core);
        for (const auto& [what, tables] : mByProblem) {
            std::string list;
            for (std::size_t i = 0; i < tables.size() && i < 5; ++i)
                list += (i ? ", " : "") + tables[i];
            if (tables.size() > 5) list += ", ...";
            error(tables.size() == 1 ? tables[0] : std::string(),
                  tables.size() == 1
                      ? what
                      : what + " in " + std::to_string(tables.size()) + " tables (" + list + ")");
        }
        meshes(level);
        tins(level);
        textures(level);
        if (level == IntegrityLevel::Deep)
            for (const auto& t : mTables) tiles(t);
        if (mTileProblems > kMaxReportedTileProblems)
            error("", std::to_string(mTileProblems - kMaxReportedTileProblems) +
                          " more tile problems not listed");
    }

private:
    void error(const std::string& where, std::string what, const char* code = "STORE_INTEGRITY") {
        mD.error(code, mDb.path(), where, std::move(what));
    }

    std::optional<std::int64_t> count(const std::string& sql, const std::string& bindText = {}) {
        auto st = mDb.prepare(sql);
        if (!st) {
            mD.append(st.diagnostics);
            return std::nullopt;
        }
        if (!bindText.empty()) st->bind(1, std::string_view(bindText));
        if (st->step() != SQLITE_ROW) return std::nullopt;
        return st->columnInt(0);
    }

    bool grid() {
        auto g = mDb.prepare(
            "SELECT srs_id, tile_width, tile_height, levels FROM kiosk_grid WHERE id = 1");
        if (!g || g->step() != SQLITE_ROW) {
            error(kGridTable, "no grid row");
            return false;
        }
        mSrs = g->columnInt(0);
        mTileW = int(g->columnInt(1));
        mTileH = int(g->columnInt(2));
        mLevels = int(g->columnInt(3));
        if (count("SELECT COUNT(*) FROM gpkg_spatial_ref_sys WHERE srs_id = " +
                  std::to_string(mSrs)) != 1)
            error("gpkg_spatial_ref_sys",
                  "no row for the store's CRS (srs_id " + std::to_string(mSrs) + ")");
        for (int mandatory : {-1, 0, 4326})
            if (count("SELECT COUNT(*) FROM gpkg_spatial_ref_sys WHERE srs_id = " +
                      std::to_string(mandatory)) != 1)
                error("gpkg_spatial_ref_sys",
                      "the mandatory row srs_id " + std::to_string(mandatory) + " is missing");
        return true;
    }

    void layers() {
        auto ls = mDb.prepare(
            "SELECT table_name, kind, levels, tile_count, description FROM kiosk_layers");
        if (!ls) {
            mD.append(ls.diagnostics);
            return;
        }
        while (ls->step() == SQLITE_ROW) {
            TileTable t;
            t.name = ls->columnText(0);
            const auto kind = parseLayerKind(ls->columnText(1));
            if (!kind) continue;  // StoreReader warns about unknown kinds
            t.scalar = *kind != LayerKind::Imagery;
            t.levels = int(ls->columnInt(2));
            t.tileCount = ls->columnInt(3);
            t.rgb = !t.scalar && declaresNormalMap(ls->columnText(4));
            // Imagery may keep its own, finer resolution below the grid (issue 16).
            const int maxLevels = mLevels + (t.scalar ? 0 : StoreWriter::kMaxExtraImageryLevels);
            if (t.levels < 1 || t.levels > maxLevels)
                error(t.name, "kiosk_layers.levels " + std::to_string(t.levels) + " outside 1.." +
                                  std::to_string(maxLevels));
            mTables.push_back(std::move(t));
        }
        // A tile table on the store's own grid, or a sequence's frame table, that kiosk_layers
        // does not list: its row was deleted (another program's tiles have their own grid).
        auto orphans = mDb.prepare(
            "SELECT c.table_name FROM gpkg_contents c JOIN gpkg_tile_matrix_set s ON "
            "s.table_name = c.table_name JOIN kiosk_grid g ON g.id = 1 WHERE c.data_type IN "
            "('tiles', '2d-gridded-coverage') AND s.srs_id = g.srs_id AND s.min_x = g.min_x AND "
            "s.min_y = g.min_y AND s.max_x = g.max_x AND s.max_y = g.max_y AND c.table_name NOT "
            "IN (SELECT table_name FROM kiosk_layers) ORDER BY c.table_name");
        if (orphans && orphans->step() == SQLITE_ROW)
            error(orphans->columnText(0),
                  "tile table on the store's grid has no kiosk_layers row (deleted?)");
    }

    void sequences() {
        if (!mDb.tableExists(kSequencesTable)) return;
        if (!mDb.tableExists(kFramesTable)) {
            error(kFramesTable, "table is missing (kiosk_sequences exists)");
            return;
        }
        auto ss = mDb.prepare("SELECT name FROM kiosk_sequences");
        if (!ss) return;
        while (ss->step() == SQLITE_ROW) {
            const std::string name = ss->columnText(0);
            auto fs = mDb.prepare(
                "SELECT frame_index, time_epoch, table_name FROM kiosk_sequence_frames WHERE "
                "sequence_name = ?1 ORDER BY frame_index");
            if (!fs) continue;
            fs->bind(1, std::string_view(name));
            std::int64_t expectIndex = 0;
            double lastTime = -INFINITY;
            bool reported = false;  // the first problem of a sequence says enough
            while (!reported && fs->step() == SQLITE_ROW) {
                const std::int64_t index = fs->columnInt(0);
                const double time = fs->columnDouble(1);
                const std::string tableName = fs->columnText(2);
                reported = true;
                if (index != expectIndex)
                    error(std::string(kFramesTable) + "/" + name,
                          "frame " + std::to_string(expectIndex) + " is missing (next is " +
                              std::to_string(index) + ")");
                else if (!(time > lastTime))
                    error(std::string(kFramesTable) + "/" + name,
                          "frame " + std::to_string(index) + " is not later than the one before");
                else if (!mDb.tableExists(tableName))
                    error(tableName, "frame table of sequence \"" + name + "\" is missing");
                else
                    reported = false;
                expectIndex = index + 1;
                lastTime = time;
            }
            if (reported) continue;
            if (expectIndex == 0) error(std::string(kSequencesTable) + "/" + name, "no frames");
            // Frame tables registered as layers but not listed as frames: rows were deleted.
            const auto orphans = count(
                "SELECT COUNT(*) FROM kiosk_layers WHERE kind = 'sequence_frame' AND table_name "
                "LIKE ?1 || '\\_f%' ESCAPE '\\' AND table_name NOT IN (SELECT table_name FROM "
                "kiosk_sequence_frames)",
                name);
            if (orphans && *orphans > 0)
                error(std::string(kFramesTable) + "/" + name,
                      std::to_string(*orphans) +
                          " frame tables are not listed in kiosk_sequence_frames");
        }
    }

    // One line per kind of problem over all tables: an emptied gpkg_contents is one message.
    void problem(const TileTable& t, const std::string& what) {
        mByProblem[what].push_back(t.name);
    }

    void table(const TileTable& t, bool perTile) {
        if (!mDb.tableExists(t.name)) {
            problem(t, "tile table is missing");
            return;
        }
        const char* type = t.scalar ? "2d-gridded-coverage" : "tiles";
        if (count("SELECT COUNT(*) FROM gpkg_contents WHERE table_name = ?1 AND data_type = '" +
                      std::string(type) + "'",
                  t.name) != 1)
            problem(t, std::string("no gpkg_contents row with data_type '") + type + "'");
        if (count("SELECT COUNT(*) FROM gpkg_tile_matrix_set WHERE table_name = ?1", t.name) != 1)
            problem(t, "no gpkg_tile_matrix_set row");
        const auto matrices = count(
            "SELECT COUNT(DISTINCT zoom_level) FROM gpkg_tile_matrix WHERE table_name = ?1 "
            "AND zoom_level BETWEEN 0 AND " +
                std::to_string(t.levels - 1) + " AND tile_width = " + std::to_string(mTileW) +
                " AND tile_height = " + std::to_string(mTileH),
            t.name);
        if (matrices.value_or(0) < t.levels)
            problem(t, "gpkg_tile_matrix lacks levels of " + std::to_string(mTileW) + "x" +
                           std::to_string(mTileH) + " tiles that kiosk_layers lists");
        if (t.scalar && count("SELECT COUNT(*) FROM gpkg_2d_gridded_coverage_ancillary WHERE "
                              "tile_matrix_set_name = ?1",
                              t.name) != 1)
            problem(t, "no gpkg_2d_gridded_coverage_ancillary row");
        if (!perTile) return;
        const std::string q = quoteIdentifier(t.name);
        const auto tiles = count("SELECT COUNT(*) FROM " + q);
        if (tiles && *tiles != t.tileCount)
            problem(t, "tile count differs from kiosk_layers.tile_count");
        if (!t.scalar) return;
        const auto noAncillary =
            count("SELECT COUNT(*) FROM " + q +
                      " t LEFT JOIN gpkg_2d_gridded_tile_ancillary a ON a.tpudt_name = ?1 AND "
                      "a.tpudt_id = t.id WHERE a.id IS NULL",
                  t.name);
        if (noAncillary.value_or(0) > 0)
            problem(t, "tiles without a gpkg_2d_gridded_tile_ancillary row (scale/offset)");
        const auto noStats =
            count("SELECT COUNT(*) FROM " + q +
                      " t LEFT JOIN kiosk_tile_stats s ON s.table_name = ?1 AND s.zoom_level = "
                      "t.zoom_level AND s.tile_column = t.tile_column AND s.tile_row = t.tile_row "
                      "WHERE s.table_name IS NULL",
                  t.name);
        if (noStats.value_or(0) > 0) problem(t, "tiles without a kiosk_tile_stats row");
    }

    // Per-tile extension tables of elevation layers (kiosk_tile_meshes, kiosk_tile_tins; both
    // optional). Core: registered; Tables: every row belongs to a tile of an elevation layer.
    // False when the table is absent or the level stops here.
    bool elevationTileRows(IntegrityLevel level, const char* table, const std::string& rows) {
        if (!mDb.tableExists(table)) return false;
        if (count("SELECT COUNT(*) FROM gpkg_extensions WHERE table_name = ?1 AND "
                  "extension_name = ?1",
                  table) != 1)
            error(table, "table is not registered in gpkg_extensions");
        if (level == IntegrityLevel::Core) return false;
        const auto foreign = count("SELECT COUNT(*) FROM " + std::string(table) +
                                   " WHERE table_name NOT IN (SELECT table_name "
                                   "FROM kiosk_layers WHERE kind = 'elevation')");
        if (foreign.value_or(0) > 0)
            error(table, std::to_string(*foreign) + " " + rows +
                             " of tables that are not elevation layers");
        for (const auto& t : mTables) {
            if (!t.scalar || !mDb.tableExists(t.name)) continue;
            const auto orphans = count("SELECT COUNT(*) FROM " + std::string(table) +
                                           " m WHERE m.table_name = ?1 AND NOT EXISTS "
                                           "(SELECT 1 FROM " +
                                           quoteIdentifier(t.name) +
                                           " t WHERE t.zoom_level = "
                                           "m.zoom_level AND t.tile_column = m.tile_column AND "
                                           "t.tile_row = m.tile_row)",
                                       t.name);
            if (orphans.value_or(0) > 0)
                error(std::string(table) + "/" + t.name,
                      std::to_string(*orphans) + " " + rows + " of tiles the table does not have");
        }
        return level == IntegrityLevel::Deep;
    }

    // kiosk_tile_meshes (stores imported before it mesh on load). Deep: every blob decodes to a
    // mesh on the grid's tiles.
    void meshes(IntegrityLevel level) {
        if (!elevationTileRows(level, kTileMeshesTable, "meshes")) return;
        auto st = mDb.prepare(
            "SELECT table_name, zoom_level, tile_column, tile_row, tier, mesh FROM "
            "kiosk_tile_meshes");
        if (!st) return;
        while (st->step() == SQLITE_ROW) {
            const TileId id{int(st->columnInt(1)), int(st->columnInt(2)), int(st->columnInt(3))};
            const std::string where =
                tileName(st->columnText(0), id) + " tier " + std::to_string(st->columnInt(4));
            const auto [data, size] = st->columnBlob(5);
            auto m = decodeMeshBlob(data, size, where);
            std::string problem;
            if (!m)
                problem = m.diagnostics.firstError()->message;
            else if (m->postIntervals != mTileW || m->postIntervals != mTileH)
                problem = "stored mesh is for " + std::to_string(m->postIntervals) +
                          "-post tiles, the grid's are " + std::to_string(mTileW);
            if (problem.empty() || ++mTileProblems > kMaxReportedTileProblems) continue;
            error(where, problem, "STORE_MESH_CORRUPT");
        }
    }

    // kiosk_tile_tins (local TINs, import breaklines / model-mesh). Deep: every blob decodes
    // (TinBlob.h checks) to a TIN of the grid's tile size.
    void tins(IntegrityLevel level) {
        if (!elevationTileRows(level, kTileTinsTable, "TINs")) return;
        auto st = mDb.prepare(
            "SELECT table_name, zoom_level, tile_column, tile_row, tin, tier FROM "
            "kiosk_tile_tins");
        if (!st) return;
        TinMesh m;
        while (st->step() == SQLITE_ROW) {
            const TileId id{int(st->columnInt(1)), int(st->columnInt(2)), int(st->columnInt(3))};
            const std::string where =
                tileName(st->columnText(0), id) + " tier " + std::to_string(st->columnInt(5));
            const auto [data, size] = st->columnBlob(4);
            Diagnostics r = decodeTinBlob(data, size, where, m);
            std::string problem;
            if (r.hasErrors())
                problem = r.firstError()->message;
            else if (m.postIntervals != mTileW || m.postIntervals != mTileH)
                problem = "stored TIN is for " + std::to_string(m.postIntervals) +
                          "-post tiles, the grid's are " + std::to_string(mTileW);
            if (problem.empty() || ++mTileProblems > kMaxReportedTileProblems) continue;
            error(where, problem, "STORE_TIN_CORRUPT");
        }
    }

    // kiosk_tile_textures (import textures; optional). Core: registered; Tables: rows only of
    // imagery tables' tiles (a data layer is never lossy-compressed); Deep: every row's sizes
    // and blob agree (TextureBlocks.h) for the grid's tile size.
    void textures(IntegrityLevel level) {
        if (!mDb.tableExists(kTileTexturesTable)) return;
        if (count("SELECT COUNT(*) FROM gpkg_extensions WHERE table_name = ?1 AND "
                  "extension_name = ?1",
                  kTileTexturesTable) != 1)
            error(kTileTexturesTable, "table is not registered in gpkg_extensions");
        if (level == IntegrityLevel::Core) return;
        const auto foreign = count(
            "SELECT COUNT(*) FROM kiosk_tile_textures WHERE table_name NOT IN (SELECT "
            "table_name FROM kiosk_layers WHERE kind = 'imagery')");
        if (foreign.value_or(0) > 0)
            error(kTileTexturesTable,
                  std::to_string(*foreign) + " textures of tables that are not imagery layers");
        for (const auto& t : mTables) {
            if (t.scalar || !mDb.tableExists(t.name)) continue;
            const auto orphans = count(
                "SELECT COUNT(*) FROM kiosk_tile_textures m WHERE m.table_name = ?1 AND NOT "
                "EXISTS (SELECT 1 FROM " +
                    quoteIdentifier(t.name) +
                    " t WHERE t.zoom_level = m.zoom_level AND t.tile_column = m.tile_column AND "
                    "t.tile_row = m.tile_row)",
                t.name);
            if (orphans.value_or(0) > 0)
                error(std::string(kTileTexturesTable) + "/" + t.name,
                      std::to_string(*orphans) + " textures of tiles the table does not have");
        }
        if (level != IntegrityLevel::Deep) return;
        auto st = mDb.prepare(
            "SELECT table_name, zoom_level, tile_column, tile_row, format, width, height, "
            "levels, length(blocks) FROM kiosk_tile_textures");
        if (!st) return;
        while (st->step() == SQLITE_ROW) {
            CompressedImage image;
            image.id = TileId{int(st->columnInt(1)), int(st->columnInt(2)), int(st->columnInt(3))};
            image.format = parseTextureFormat(st->columnText(4)).value_or(TextureFormat::None);
            image.width = int(st->columnInt(5));
            image.height = int(st->columnInt(6));
            image.levels = int(st->columnInt(7));
            const std::string where = tileName(st->columnText(0), image.id);
            Diagnostics r =
                checkCompressedImage(image, std::size_t(st->columnInt(8)), mDb.path(), where);
            std::string problem;
            if (r.hasErrors())
                problem = r.firstError()->message;
            else if (image.width != mTileW || image.height != mTileH)
                problem = "stored texture is " + std::to_string(image.width) + "x" +
                          std::to_string(image.height) + ", the grid's tiles " +
                          std::to_string(mTileW) + "x" + std::to_string(mTileH);
            if (problem.empty() || ++mTileProblems > kMaxReportedTileProblems) continue;
            error(where, problem, "STORE_TEXTURE_CORRUPT");
        }
    }

    void tiles(const TileTable& t) {
        if (!mDb.tableExists(t.name)) return;
        auto st = mDb.prepare("SELECT zoom_level, tile_column, tile_row, tile_data FROM " +
                              quoteIdentifier(t.name));
        if (!st) return;
        while (st->step() == SQLITE_ROW) {
            const TileId id{int(st->columnInt(0)), int(st->columnInt(1)), int(st->columnInt(2))};
            const auto [data, size] = st->columnBlob(3);
            const std::string where = tileName(t.name, id);
            Diagnostics tile =
                checkTileHeader(data, size, {mTileW, mTileH, t.scalar, t.rgb}, where);
            if (!tile.hasErrors()) {
                // Decode: the header can be right and the pixels still broken.
                if (t.scalar) {
                    auto r = decodeGray16(data, size, where);
                    if (!r) tile = r.diagnostics;
                } else {
                    auto r = decodeRgba8(data, size, where);
                    if (!r) tile = r.diagnostics;
                }
            }
            for (Diagnostic e : tile.items()) {
                if (e.severity != Severity::Error) continue;
                if (++mTileProblems > kMaxReportedTileProblems) break;
                e.file = mDb.path();
                if (e.code == "IMAGE_DECODE") e.code = "STORE_TILE_CORRUPT";
                mD.add(std::move(e));
                break;
            }
        }
    }

    SqliteDb& mDb;
    Diagnostics& mD;
    std::int64_t mSrs = 0;
    int mTileW = 0, mTileH = 0, mLevels = 0;
    std::vector<TileTable> mTables;
    std::map<std::string, std::vector<std::string>> mByProblem;  // problem -> tables
    int mTileProblems = 0;
};

}  // namespace

Diagnostics checkStoreIntegrity(const std::filesystem::path& path, IntegrityLevel level) {
    Diagnostics d;
    auto db = SqliteDb::open(path, SqliteDb::Mode::ReadOnly);
    if (!db) return db.diagnostics;
    Checker(*db, d).run(level);
    return d;
}

}  // namespace kiosk::io
