#pragma once

#include "runtime/core/Result.h"

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kiosk::io {

struct SqliteStatementDeleter {
    void operator()(sqlite3_stmt* s) const noexcept { sqlite3_finalize(s); }
};
using SqliteStatementPtr = std::unique_ptr<sqlite3_stmt, SqliteStatementDeleter>;

/**
 * @brief A prepared statement with checked binds and steps (cesium-native's SqliteStatementPtr
 * plus small helpers). Move-only; finalised on destruction. Not thread-safe: belongs to the
 * thread that owns its SqliteDb.
 */
class Statement {
public:
    Statement() = default;
    explicit Statement(SqliteStatementPtr s) : mStmt(std::move(s)) {}

    bool valid() const noexcept { return mStmt != nullptr; }
    sqlite3_stmt* get() const noexcept { return mStmt.get(); }

    /** @brief Reset for re-use and clear bindings. */
    void reset() noexcept;
    /** @brief Bind helpers; index is 1-based like SQLite's. Return the SQLite code. */
    int bind(int index, std::int64_t v) noexcept;
    int bind(int index, double v) noexcept;
    int bind(int index, std::string_view v) noexcept;
    int bindBlob(int index, const void* data, std::size_t size) noexcept;
    int bindNull(int index) noexcept;
    int bindInt(int index, int v) noexcept { return bind(index, std::int64_t(v)); }

    /** @brief SQLITE_ROW, SQLITE_DONE or an error code. */
    int step() noexcept;

    std::int64_t columnInt(int col) const noexcept;
    double columnDouble(int col) const noexcept;
    std::string columnText(int col) const;
    bool columnIsNull(int col) const noexcept;
    /** @brief Blob bytes, valid until the next step/reset. */
    std::pair<const std::uint8_t*, std::size_t> columnBlob(int col) const noexcept;

private:
    SqliteStatementPtr mStmt;
};

/**
 * @brief Move-only SQLite connection. Errors come back as Diagnostics carrying the file name,
 * the SQL (or table) involved and sqlite3_errmsg. Not thread-safe: one per thread
 * (opened NOMUTEX).
 */
class SqliteDb {
public:
    enum class Mode { ReadOnly, ReadWrite, Create };

    SqliteDb() = default;
    ~SqliteDb();
    SqliteDb(SqliteDb&& o) noexcept;
    SqliteDb& operator=(SqliteDb&& o) noexcept;
    SqliteDb(const SqliteDb&) = delete;
    SqliteDb& operator=(const SqliteDb&) = delete;

    /** @brief Open `path`; code STORE_OPEN on failure. */
    static Result<SqliteDb> open(const std::filesystem::path& path, Mode mode);

    sqlite3* handle() const noexcept { return mDb; }
    const std::string& path() const noexcept { return mPath; }

    /** @brief Run one or more statements without results; code STORE_SQL on failure. */
    Diagnostics exec(std::string_view sql);
    /** @brief Prepare a statement; code STORE_SQL on failure. */
    Result<Statement> prepare(std::string_view sql);
    /** @brief First column of the first row as integer, nullopt if no row or on error. */
    std::optional<std::int64_t> queryInt(std::string_view sql);
    /** @brief True if a table (or view) of that name exists. */
    bool tableExists(std::string_view name);

    /** @brief Last SQLite error message of this connection. */
    std::string errorMessage() const;
    /** @brief An error diagnostic for the last failure: `file: where: what: sqlite message`. */
    Diagnostic error(std::string code, std::string where, std::string what) const;

    void close() noexcept;

private:
    sqlite3* mDb = nullptr;
    std::string mPath;
};

/** @brief Quote an identifier for SQL ("name" with embedded quotes doubled). */
std::string quoteIdentifier(std::string_view name);

}  // namespace kiosk::io
