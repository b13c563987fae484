#include "runtime/io/SqliteDb.h"

#include <utility>

namespace kiosk::io {

void Statement::reset() noexcept {
    if (!mStmt) return;
    sqlite3_reset(mStmt.get());
    sqlite3_clear_bindings(mStmt.get());
}

int Statement::bind(int index, std::int64_t v) noexcept {
    return sqlite3_bind_int64(mStmt.get(), index, sqlite3_int64(v));
}
int Statement::bind(int index, double v) noexcept {
    return sqlite3_bind_double(mStmt.get(), index, v);
}
int Statement::bind(int index, std::string_view v) noexcept {
    return sqlite3_bind_text64(mStmt.get(), index, v.data(), sqlite3_uint64(v.size()),
                               SQLITE_TRANSIENT, SQLITE_UTF8);
}
int Statement::bindBlob(int index, const void* data, std::size_t size) noexcept {
    return sqlite3_bind_blob64(mStmt.get(), index, data, sqlite3_uint64(size), SQLITE_TRANSIENT);
}
int Statement::bindNull(int index) noexcept {
    return sqlite3_bind_null(mStmt.get(), index);
}

int Statement::step() noexcept {
    return sqlite3_step(mStmt.get());
}

std::int64_t Statement::columnInt(int col) const noexcept {
    return std::int64_t(sqlite3_column_int64(mStmt.get(), col));
}
double Statement::columnDouble(int col) const noexcept {
    return sqlite3_column_double(mStmt.get(), col);
}
std::string Statement::columnText(int col) const {
    const unsigned char* t = sqlite3_column_text(mStmt.get(), col);
    return t ? std::string(reinterpret_cast<const char*>(t)) : std::string();
}
bool Statement::columnIsNull(int col) const noexcept {
    return sqlite3_column_type(mStmt.get(), col) == SQLITE_NULL;
}
std::pair<const std::uint8_t*, std::size_t> Statement::columnBlob(int col) const noexcept {
    const void* p = sqlite3_column_blob(mStmt.get(), col);
    const int n = sqlite3_column_bytes(mStmt.get(), col);
    return {static_cast<const std::uint8_t*>(p), std::size_t(n < 0 ? 0 : n)};
}

SqliteDb::~SqliteDb() {
    close();
}

SqliteDb::SqliteDb(SqliteDb&& o) noexcept
    : mDb(std::exchange(o.mDb, nullptr)), mPath(std::move(o.mPath)) {}

SqliteDb& SqliteDb::operator=(SqliteDb&& o) noexcept {
    if (this != &o) {
        close();
        mDb = std::exchange(o.mDb, nullptr);
        mPath = std::move(o.mPath);
    }
    return *this;
}

void SqliteDb::close() noexcept {
    if (mDb) {
        // close_v2 defers the close until leftover statements are finalised, so a statement
        // outliving its connection is not a use-after-free.
        sqlite3_close_v2(mDb);
        mDb = nullptr;
    }
}

Result<SqliteDb> SqliteDb::open(const std::filesystem::path& path, Mode mode) {
    int flags = SQLITE_OPEN_NOMUTEX;
    switch (mode) {
        case Mode::ReadOnly:
            flags |= SQLITE_OPEN_READONLY;
            break;
        case Mode::ReadWrite:
            flags |= SQLITE_OPEN_READWRITE;
            break;
        case Mode::Create:
            flags |= SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
            break;
    }
    SqliteDb db;
    db.mPath = path.string();
    const int rc = sqlite3_open_v2(db.mPath.c_str(), &db.mDb, flags, nullptr);
    if (rc != SQLITE_OK) {
        Diagnostics d;
        d.error("STORE_OPEN", db.mPath, "",
                std::string("cannot open store: ") +
                    (db.mDb ? sqlite3_errmsg(db.mDb) : sqlite3_errstr(rc)));
        return d;
    }
    // A reader racing an appending writer waits a little instead of failing at once.
    sqlite3_busy_timeout(db.mDb, 2000);
    sqlite3_extended_result_codes(db.mDb, 1);
    return Result<SqliteDb>(std::move(db));
}

Diagnostics SqliteDb::exec(std::string_view sql) {
    Diagnostics d;
    char* err = nullptr;
    const std::string s(sql);
    if (sqlite3_exec(mDb, s.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
        d.error("STORE_SQL", mPath, "",
                std::string(err ? err : "error") + " in: " + s.substr(0, 120));
        sqlite3_free(err);
    }
    return d;
}

Result<Statement> SqliteDb::prepare(std::string_view sql) {
    sqlite3_stmt* raw = nullptr;
    const int rc = sqlite3_prepare_v2(mDb, sql.data(), int(sql.size()), &raw, nullptr);
    if (rc != SQLITE_OK) {
        Diagnostics d;
        d.error("STORE_SQL", mPath, "", errorMessage() + " in: " + std::string(sql.substr(0, 120)));
        return d;
    }
    return Statement(SqliteStatementPtr(raw));
}

std::optional<std::int64_t> SqliteDb::queryInt(std::string_view sql) {
    auto st = prepare(sql);
    if (!st) return std::nullopt;
    if (st->step() != SQLITE_ROW || st->columnIsNull(0)) return std::nullopt;
    return st->columnInt(0);
}

bool SqliteDb::tableExists(std::string_view name) {
    auto st = prepare("SELECT 1 FROM sqlite_master WHERE type IN ('table','view') AND name = ?");
    if (!st) return false;
    st->bind(1, name);
    return st->step() == SQLITE_ROW;
}

std::string SqliteDb::errorMessage() const {
    return mDb ? std::string(sqlite3_errmsg(mDb)) : std::string("no connection");
}

Diagnostic SqliteDb::error(std::string code, std::string where, std::string what) const {
    Diagnostic d;
    d.code = std::move(code);
    d.file = mPath;
    d.where = std::move(where);
    d.message = std::move(what) + ": " + errorMessage();
    return d;
}

std::string quoteIdentifier(std::string_view name) {
    std::string out = "\"";
    for (char c : name) {
        if (c == '"') out += '"';
        out += c;
    }
    out += '"';
    return out;
}

}  // namespace kiosk::io
