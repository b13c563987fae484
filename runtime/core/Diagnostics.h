#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace kiosk {

enum class Severity { Error, Warning };

/**
 * @brief One problem found in user input or data.
 *
 * `code` is stable (tests and remote monitoring match it, not the prose). `file` and `where`
 * locate the culprit: `where` is a JSON pointer, a table/tile name or empty.
 * Formatted as `file[:line:col]: [where: ]message (hint)`, see docs/cli.md.
 */
struct Diagnostic {
    Severity severity = Severity::Error;
    std::string code;
    std::string file;
    int line = 0;    ///< 1-based; 0 when unknown
    int column = 0;  ///< 1-based; 0 when unknown
    std::string where;
    std::string message;
    std::string hint;

    std::string format() const;
};

/** @brief Errors and warnings collected while doing one job (Cesium's ErrorList). */
class Diagnostics {
public:
    Diagnostic& error(std::string code, std::string file, std::string where, std::string message);
    Diagnostic& warning(std::string code, std::string file, std::string where,
                        std::string message);
    void add(Diagnostic d) { mItems.push_back(std::move(d)); }
    void append(const Diagnostics& other);

    bool hasErrors() const noexcept;
    bool empty() const noexcept { return mItems.empty(); }
    std::size_t size() const noexcept { return mItems.size(); }
    const std::vector<Diagnostic>& items() const noexcept { return mItems; }
    /** @brief True if any diagnostic carries this code. */
    bool has(std::string_view code) const noexcept;
    /** @brief First error, or nullptr. */
    const Diagnostic* firstError() const noexcept;

    /** @brief Every diagnostic, one line each, errors and warnings in order. */
    std::string format() const;

private:
    std::vector<Diagnostic> mItems;
};

}  // namespace kiosk
