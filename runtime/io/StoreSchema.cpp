#include "runtime/io/StoreSchema.h"

#include "runtime/io/StoreTables.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <string>
#include <vector>

namespace kiosk::io {

namespace {

// SQLite's column affinity of a declared type (https://sqlite.org/datatype3.html §3.1): what
// decides how a value is stored, so DOUBLE and REAL, or INT and INTEGER, are the same here.
enum class Affinity { Integer, Text, Blob, Real, Numeric };

Affinity affinityOf(std::string type) {
    std::transform(type.begin(), type.end(), type.begin(),
                   [](unsigned char c) { return char(std::toupper(c)); });
    const auto has = [&](const char* s) { return type.find(s) != std::string::npos; };
    if (has("INT")) return Affinity::Integer;
    if (has("CHAR") || has("CLOB") || has("TEXT")) return Affinity::Text;
    if (has("BLOB") || type.empty()) return Affinity::Blob;
    if (has("REAL") || has("FLOA") || has("DOUB")) return Affinity::Real;
    return Affinity::Numeric;
}

struct Column {
    const char* name;
    const char* type;  // as the writer declares it
};

struct TableSchema {
    const char* table;
    std::vector<Column> columns;
};

// The columns readers and checks use, as StoreWriter*.cpp creates them.
const std::vector<TableSchema>& formatTables() {
    static const std::vector<TableSchema> tables = {
        {"gpkg_spatial_ref_sys",
         {{"srs_name", "TEXT"},
          {"srs_id", "INTEGER"},
          {"organization", "TEXT"},
          {"organization_coordsys_id", "INTEGER"},
          {"definition", "TEXT"}}},
        {"gpkg_contents",
         {{"table_name", "TEXT"},
          {"data_type", "TEXT"},
          {"identifier", "TEXT"},
          {"min_x", "DOUBLE"},
          {"min_y", "DOUBLE"},
          {"max_x", "DOUBLE"},
          {"max_y", "DOUBLE"},
          {"srs_id", "INTEGER"}}},
        {"gpkg_tile_matrix_set",
         {{"table_name", "TEXT"},
          {"srs_id", "INTEGER"},
          {"min_x", "DOUBLE"},
          {"min_y", "DOUBLE"},
          {"max_x", "DOUBLE"},
          {"max_y", "DOUBLE"}}},
        {"gpkg_tile_matrix",
         {{"table_name", "TEXT"},
          {"zoom_level", "INTEGER"},
          {"matrix_width", "INTEGER"},
          {"matrix_height", "INTEGER"},
          {"tile_width", "INTEGER"},
          {"tile_height", "INTEGER"},
          {"pixel_x_size", "DOUBLE"},
          {"pixel_y_size", "DOUBLE"}}},
        {"gpkg_extensions",
         {{"table_name", "TEXT"},
          {"column_name", "TEXT"},
          {"extension_name", "TEXT"},
          {"definition", "TEXT"},
          {"scope", "TEXT"}}},
        {"gpkg_2d_gridded_coverage_ancillary",
         {{"tile_matrix_set_name", "TEXT"},
          {"datatype", "TEXT"},
          {"scale", "REAL"},
          {"offset", "REAL"},
          {"precision", "REAL"},
          {"data_null", "REAL"}}},
        {"gpkg_2d_gridded_tile_ancillary",
         {{"id", "INTEGER"},
          {"tpudt_name", "TEXT"},
          {"tpudt_id", "INTEGER"},
          {"scale", "REAL"},
          {"offset", "REAL"}}},
        {kGridTable,
         {{"id", "INTEGER"},
          {"srs_id", "INTEGER"},
          {"min_x", "DOUBLE"},
          {"min_y", "DOUBLE"},
          {"max_x", "DOUBLE"},
          {"max_y", "DOUBLE"},
          {"tile_width", "INTEGER"},
          {"tile_height", "INTEGER"},
          {"levels", "INTEGER"},
          {"finest_pixel_size", "DOUBLE"}}},
        {kLayersTable,
         {{"table_name", "TEXT"},
          {"kind", "TEXT"},
          {"units", "TEXT"},
          {"min_value", "DOUBLE"},
          {"max_value", "DOUBLE"},
          {"nodata", "DOUBLE"},
          {"data_min_x", "DOUBLE"},
          {"data_min_y", "DOUBLE"},
          {"data_max_x", "DOUBLE"},
          {"data_max_y", "DOUBLE"},
          {"levels", "INTEGER"},
          {"tile_count", "INTEGER"},
          {"precision", "DOUBLE"},
          {"description", "TEXT"}}},
        {kTileStatsTable,
         {{"table_name", "TEXT"},
          {"zoom_level", "INTEGER"},
          {"tile_column", "INTEGER"},
          {"tile_row", "INTEGER"},
          {"min_value", "DOUBLE"},
          {"max_value", "DOUBLE"},
          {"geometric_error", "DOUBLE"},
          {"border_posts", "BLOB"}}},
        {kSequencesTable,
         {{"name", "TEXT"},
          {"units", "TEXT"},
          {"variable", "TEXT"},
          {"categorical", "INTEGER"},
          {"nodata", "DOUBLE"}}},
        {kFramesTable,
         {{"sequence_name", "TEXT"},
          {"frame_index", "INTEGER"},
          {"time_utc", "TEXT"},
          {"time_epoch", "DOUBLE"},
          {"table_name", "TEXT"},
          {"min_value", "DOUBLE"},
          {"max_value", "DOUBLE"}}},
        {kTileMeshesTable,
         {{"table_name", "TEXT"},
          {"zoom_level", "INTEGER"},
          {"tile_column", "INTEGER"},
          {"tile_row", "INTEGER"},
          {"tier", "INTEGER"},
          {"tolerance", "DOUBLE"},
          {"split_tiers", "INTEGER"},
          {"mesh", "BLOB"}}},
        {kTileTinsTable,
         {{"table_name", "TEXT"},
          {"zoom_level", "INTEGER"},
          {"tile_column", "INTEGER"},
          {"tile_row", "INTEGER"},
          {"tier", "INTEGER"},
          {"tolerance", "DOUBLE"},
          {"tin", "BLOB"}}},
        {kTileTexturesTable,
         {{"table_name", "TEXT"},
          {"zoom_level", "INTEGER"},
          {"tile_column", "INTEGER"},
          {"tile_row", "INTEGER"},
          {"format", "TEXT"},
          {"width", "INTEGER"},
          {"height", "INTEGER"},
          {"levels", "INTEGER"},
          {"blocks", "BLOB"}}},
    };
    return tables;
}

const std::vector<Column>& tileTableColumns() {
    static const std::vector<Column> columns = {{"id", "INTEGER"},
                                                {"zoom_level", "INTEGER"},
                                                {"tile_column", "INTEGER"},
                                                {"tile_row", "INTEGER"},
                                                {"tile_data", "BLOB"}};
    return columns;
}

// False (and one error) at the first expected column that is absent or of another affinity.
bool compare(SqliteDb& db, const std::string& table, const std::vector<Column>& expected,
             Diagnostics& d) {
    auto info = db.prepare("SELECT name, type FROM pragma_table_info(?1)");
    if (!info) {
        d.append(info.diagnostics);
        return false;
    }
    info->bind(1, std::string_view(table));
    std::vector<std::pair<std::string, std::string>> actual;
    while (info->step() == SQLITE_ROW)
        actual.emplace_back(info->columnText(0), info->columnText(1));
    for (const Column& c : expected) {
        // SQLite's own rule: column names compare case-insensitively.
        const auto it = std::find_if(actual.begin(), actual.end(), [&](const auto& a) {
            return a.first.size() == std::string_view(c.name).size() &&
                   std::equal(a.first.begin(), a.first.end(), c.name, [](char x, char y) {
                       return std::tolower(static_cast<unsigned char>(x)) ==
                              std::tolower(static_cast<unsigned char>(y));
                   });
        });
        if (it == actual.end()) {
            d.error("STORE_SCHEMA", db.path(), table,
                    std::string("column ") + c.name + " is missing (the store format has " +
                        c.name + " " + c.type + "; renamed or dropped?)");
            return false;
        }
        if (affinityOf(it->second) != affinityOf(c.type)) {
            d.error("STORE_SCHEMA", db.path(), table,
                    std::string("column ") + c.name + " is declared " +
                        (it->second.empty() ? std::string("without a type") : it->second) +
                        "; the store format has " + c.type);
            return false;
        }
    }
    return true;
}

}  // namespace

Diagnostics checkStoreSchema(SqliteDb& db) {
    Diagnostics d;
    for (const TableSchema& t : formatTables())
        if (db.tableExists(t.table) && !compare(db, t.table, t.columns, d)) return d;
    std::set<std::string> tileTables;
    for (const char* sql :
         {"SELECT table_name FROM kiosk_layers", "SELECT table_name FROM kiosk_sequence_frames"}) {
        if (!db.tableExists(std::string_view(sql).substr(std::string_view(sql).rfind(' ') + 1)))
            continue;
        auto st = db.prepare(sql);
        if (!st) return st.diagnostics;
        while (st->step() == SQLITE_ROW) tileTables.insert(st->columnText(0));
    }
    for (const std::string& t : tileTables)
        if (db.tableExists(t) && !compare(db, t, tileTableColumns(), d)) return d;
    return d;
}

}  // namespace kiosk::io
