#include "runtime/io/StorePages.h"

#include <map>
#include <string>
#include <vector>

namespace kiosk::io {

namespace {

// quick_check names b-trees by their root page ("Tree 7 page 12 cell 3: ..."): say the table.
std::string nameTrees(const std::string& message,
                      const std::map<std::int64_t, std::string>& roots) {
    const std::size_t at = message.find("Tree ");
    if (at == std::string::npos) return message;
    std::size_t end = at + 5;
    std::int64_t root = 0;
    while (end < message.size() && message[end] >= '0' && message[end] <= '9')
        root = root * 10 + (message[end++] - '0');
    const auto it = roots.find(root);
    if (end == at + 5 || it == roots.end()) return message;
    return message.substr(0, end) + " (" + it->second + ")" + message.substr(end);
}

// False when quick_check itself stopped on a page it cannot read (then the rows say where).
bool quickCheck(SqliteDb& db, const std::map<std::int64_t, std::string>& roots, Diagnostics& d) {
    auto st = db.prepare("PRAGMA quick_check(100)");
    if (!st) return false;
    std::vector<std::string> problems;
    int rc = SQLITE_ROW;
    while ((rc = st->step()) == SQLITE_ROW) {
        std::string line = st->columnText(0);
        if (line != "ok") problems.push_back(nameTrees(line, roots));
    }
    if (rc != SQLITE_DONE) return false;
    if (problems.empty()) return true;
    for (char& c : problems[0])
        if (c == '\n') c = ' ';
    d.error("STORE_CORRUPT", db.path(), "",
            "SQLite quick_check: " + problems[0] +
                (problems.size() > 1
                     ? " (and " + std::to_string(problems.size() - 1) +
                           (problems.size() == 100 ? " or more" : "") + " more problems)"
                     : ""));
    return true;
}

void readEveryRow(SqliteDb& db, const std::string& table, Diagnostics& d) {
    auto st = db.prepare("SELECT * FROM " + quoteIdentifier(table));
    if (!st) {
        d.add(db.error("STORE_CORRUPT", table, "cannot read the table"));
        return;
    }
    sqlite3_stmt* s = st->get();
    const int columns = sqlite3_column_count(s);
    std::int64_t rows = 0;
    int rc = SQLITE_ROW;
    while ((rc = st->step()) == SQLITE_ROW) {
        // The byte count makes SQLite load the value: for blobs and text, their overflow pages.
        for (int c = 0; c < columns; ++c)
            if (sqlite3_column_type(s, c) == SQLITE_BLOB)
                (void)sqlite3_column_blob(s, c);
            else
                (void)sqlite3_column_text(s, c);
        ++rows;
    }
    if (rc != SQLITE_DONE)
        d.add(db.error("STORE_CORRUPT", table,
                       "cannot read row " + std::to_string(rows + 1) + " (after " +
                           std::to_string(rows) + " rows)"));
}

}  // namespace

Diagnostics checkStorePages(SqliteDb& db) {
    Diagnostics d;
    std::map<std::int64_t, std::string> roots;
    std::vector<std::string> tables;
    {
        auto st = db.prepare(
            "SELECT name, rootpage, type FROM sqlite_schema WHERE rootpage > 0 ORDER BY name");
        if (!st) return st.diagnostics;
        while (st->step() == SQLITE_ROW) {
            roots[st->columnInt(1)] = st->columnText(0);
            if (st->columnText(2) == "table") tables.push_back(st->columnText(0));
        }
    }
    // quick_check's findings are the whole story; the rows only add the same pages again.
    const bool checked = quickCheck(db, roots, d);
    if (d.hasErrors()) return d;
    for (const std::string& t : tables) readEveryRow(db, t, d);
    if (!checked && !d.hasErrors())
        d.add(db.error("STORE_CORRUPT", "", "SQLite quick_check stopped"));
    return d;
}

}  // namespace kiosk::io
