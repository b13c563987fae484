#include "runtime/io/StoreMetadata.h"

#include "runtime/io/StoreTables.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace kiosk::io {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFloatMax = double(std::numeric_limits<float>::max());

// A column's allowed values: a number (SQLite integer or real; text such as 'NaN' is not) in
// [lo, hi], or (lo, hi] when `loOpen`; NULL only when `nullable`.
struct Bound {
    const char* column;
    double lo, hi;
    bool loOpen = false;
    bool nullable = false;
};

// A condition over a row's columns, checked once its bounds hold; `what` says what it wants.
struct Relation {
    std::string sql;
    std::string what;
};

struct TableRule {
    const char* table;
    std::string label;   // SQL naming a row, e.g. table_name || '/' || zoom_level
    std::string filter;  // SQL WHERE clause, or empty
    std::vector<Bound> bounds;
    std::vector<Relation> relations;
};

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", v);
    return text;
}

std::string range(const Bound& b) {
    if (b.lo == -b.hi && b.hi >= kFloatMax) return "a finite number";
    return std::string(b.loOpen ? "(" : "[") + number(b.lo) + ", " + number(b.hi) + "]";
}

const char* const kOurTables = "table_name IN (SELECT table_name FROM kiosk_layers)";

std::vector<Bound> extent(const char* minX, const char* minY, const char* maxX, const char* maxY,
                          bool nullable) {
    const double m = kMaxStoreCoordinate;
    return {{minX, -m, m, false, nullable},
            {minY, -m, m, false, nullable},
            {maxX, -m, m, false, nullable},
            {maxY, -m, m, false, nullable}};
}

std::vector<TableRule> rules(int tileWidth, int tileHeight) {
    const Relation ordered{"min_x < max_x AND min_y < max_y", "min_x < max_x and min_y < max_y"};
    std::vector<TableRule> r;
    {
        TableRule t{
            kGridTable, "'grid'", "", extent("min_x", "min_y", "max_x", "max_y", false), {ordered}};
        t.bounds.push_back({"tile_width", 1, 4096});
        t.bounds.push_back({"tile_height", 1, 4096});
        t.bounds.push_back({"levels", 1, 30});
        t.bounds.push_back({"finest_pixel_size", 0, kMaxStorePixelSize, true});
        r.push_back(std::move(t));
    }
    r.push_back({"gpkg_tile_matrix_set",
                 "table_name",
                 kOurTables,
                 extent("min_x", "min_y", "max_x", "max_y", false),
                 {ordered}});
    r.push_back({"gpkg_tile_matrix",
                 "table_name || '/' || zoom_level",
                 kOurTables,
                 {{"zoom_level", 0, 33},
                  {"matrix_width", 1, 8589934592.0},
                  {"matrix_height", 1, 8589934592.0},
                  {"tile_width", 1, 4096},
                  {"tile_height", 1, 4096},
                  {"pixel_x_size", 0, kMaxStorePixelSize, true},
                  {"pixel_y_size", 0, kMaxStorePixelSize, true}},
                 {{"matrix_width = (1 << zoom_level) AND matrix_height = (1 << zoom_level)",
                   "matrix_width = matrix_height = 2^zoom_level (level L is 2^L x 2^L tiles)"}}});
    r.push_back({"gpkg_2d_gridded_coverage_ancillary",
                 "tile_matrix_set_name",
                 "tile_matrix_set_name IN (SELECT table_name FROM kiosk_layers)",
                 {{"scale", 0, 1e6, true},
                  {"offset", -1e9, 1e9},
                  {"precision", 0, 1e9, false, true},
                  {"data_null", 0, 65535, false, true}},
                 {}});
    r.push_back({"gpkg_2d_gridded_tile_ancillary",
                 "tpudt_name || ' tile id ' || tpudt_id",
                 "tpudt_name IN (SELECT table_name FROM kiosk_layers)",
                 {{"scale", 0, 1e6, true}, {"offset", -1e9, 1e9}},
                 {}});
    {
        TableRule t{kLayersTable,
                    "table_name",
                    "",
                    extent("data_min_x", "data_min_y", "data_max_x", "data_max_y", true),
                    {}};
        t.bounds.push_back({"min_value", -kFloatMax, kFloatMax, false, true});
        t.bounds.push_back({"max_value", -kFloatMax, kFloatMax, false, true});
        t.bounds.push_back({"nodata", -kInf, kInf, false, true});
        t.bounds.push_back({"levels", 1, 33});
        t.bounds.push_back({"tile_count", 0, 1e12});
        t.bounds.push_back({"precision", 0, 1e9, false, true});
        r.push_back(std::move(t));
    }
    const std::string borderBytes = std::to_string((tileHeight + 1 + tileWidth) * 4);
    r.push_back({kTileStatsTable,
                 "table_name || '/' || zoom_level || '/' || tile_column || '/' || tile_row",
                 "",
                 {{"min_value", -kFloatMax, kFloatMax},
                  {"max_value", -kFloatMax, kFloatMax},
                  {"geometric_error", 0, kFloatMax}},
                 {{"min_value <= max_value", "min_value <= max_value"},
                  {"border_posts IS NULL OR (typeof(border_posts) = 'blob' AND "
                   "length(border_posts) IN (0, " +
                       borderBytes + "))",
                   "border_posts of " + borderBytes + " bytes (" +
                       std::to_string(tileHeight + 1 + tileWidth) + " float32 posts)"}}});
    r.push_back({kSequencesTable,
                 "name",
                 "",
                 {{"categorical", 0, 1}, {"nodata", -kInf, kInf, false, true}},
                 {}});
    r.push_back({kFramesTable,
                 "sequence_name || ' frame ' || frame_index",
                 "",
                 {{"frame_index", 0, 1e9},
                  {"time_epoch", -1e11, 1e11},
                  {"min_value", -kFloatMax, kFloatMax, false, true},
                  {"max_value", -kFloatMax, kFloatMax, false, true}},
                 {}});
    return r;
}

// "" when the value in columns (type, value) of `st` at `col` is within `b`, else the problem.
std::string valueProblem(const Statement& st, int col, const Bound& b) {
    const std::string type = st.columnText(col);
    if (type == "null") return b.nullable ? "" : "is NULL";
    if (type != "integer" && type != "real") {
        std::string shown = st.columnText(col + 1);
        if (shown.size() > 24) shown = shown.substr(0, 24) + "...";
        return "is " + type + (type == "text" ? " '" + shown + "'" : "") + ", not a number";
    }
    const double v = st.columnDouble(col + 1);
    const bool ok = std::isfinite(v) && (b.loOpen ? v > b.lo : v >= b.lo) && v <= b.hi;
    return ok ? "" : "is " + number(v);
}

void checkTable(SqliteDb& db, const TableRule& t, Diagnostics& d) {
    if (!db.tableExists(t.table)) return;
    std::string sql = "SELECT " + t.label;
    for (const Bound& b : t.bounds) sql += std::string(", typeof(") + b.column + "), " + b.column;
    for (const Relation& rel : t.relations) sql += ", coalesce((" + rel.sql + "), 0)";
    sql += std::string(" FROM ") + t.table + (t.filter.empty() ? "" : " WHERE " + t.filter);
    auto st = db.prepare(sql);
    if (!st) {
        d.append(st.diagnostics);
        return;
    }
    std::string firstRow, firstProblem;
    std::int64_t bad = 0;
    while (st->step() == SQLITE_ROW) {
        std::string problem;
        int col = 1;
        for (const Bound& b : t.bounds) {
            if (problem.empty()) {
                const std::string p = valueProblem(*st, col, b);
                if (!p.empty()) problem = std::string(b.column) + " " + p + ", wants " + range(b);
            }
            col += 2;
        }
        for (const Relation& rel : t.relations) {
            if (problem.empty() && st->columnInt(col) == 0) problem = "wants " + rel.what;
            ++col;
        }
        if (problem.empty()) continue;
        if (bad++ == 0) {
            firstRow = st->columnText(0);
            firstProblem = std::move(problem);
        }
    }
    if (bad == 0) return;
    d.error("STORE_METADATA", db.path(), std::string(t.table) + "/" + firstRow,
            firstProblem + (bad > 1 ? " (and " + std::to_string(bad - 1) + " more rows)" : ""));
}

}  // namespace

Diagnostics checkStoreMetadata(SqliteDb& db) {
    Diagnostics d;
    int tileWidth = 0, tileHeight = 0;
    if (auto g = db.prepare("SELECT tile_width, tile_height FROM kiosk_grid WHERE id = 1");
        g && g->step() == SQLITE_ROW) {
        tileWidth = int(g->columnInt(0));
        tileHeight = int(g->columnInt(1));
    }
    for (const TableRule& t : rules(tileWidth, tileHeight)) checkTable(db, t, d);
    return d;
}

}  // namespace kiosk::io
