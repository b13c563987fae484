#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

// Where each JSON value of a scenario came from: nlohmann::json keeps no positions, so a small
// scanner indexes the text once (JSON pointer -> line:column of the value and of its key).
namespace kiosk::config {

/** @brief A place in a source file; line and column are 1-based, 0 when unknown. */
struct Location {
    std::string file;
    int line = 0;
    int column = 0;
};

/** @brief Escape one reference token for a JSON pointer (RFC 6901: ~ -> ~0, / -> ~1). */
std::string escapePointerToken(std::string_view token);
/** @brief `parent + "/" + escape(token)`. */
std::string childPointer(std::string_view parent, std::string_view token);
inline std::string childPointer(std::string_view parent, std::size_t index) {
    return std::string(parent) + "/" + std::to_string(index);
}

/**
 * @brief Items of one array, members of one object, whose positions are kept. The largest limit
 * on one container (config/Limits.h) is 4096, so a scenario with more is refused anyway; keeping
 * the positions of a 220,000-stop list would cost hundreds of MB before it is.
 */
inline constexpr std::size_t kMaxIndexedItems = 4097;

/** @brief Positions inside one text, by JSON pointer. Built by indexJsonText(). */
struct TextIndex {
    struct Pos {
        int line = 0;
        int column = 0;
    };
    std::map<std::string, Pos, std::less<>> values;  ///< where each value starts
    std::map<std::string, Pos, std::less<>> keys;    ///< where each member's key starts
    std::vector<std::string> duplicateKeys;          ///< pointers of members given twice
    int maxDepth = 0;                                ///< deepest nesting seen
    bool complete = true;  ///< false if the scanner stopped early (malformed or too deep)
};

/**
 * @brief Index a JSON text (comments `//` and `/ * * /` allowed, as the reader allows them).
 * Never throws, never recurses deeper than `depthLimit` (deeper values are not indexed and
 * `complete` is false). Items past the first kMaxIndexedItems of a container are scanned but
 * not indexed. Columns count UTF-8 code points, not bytes.
 */
TextIndex indexJsonText(std::string_view text, int depthLimit = 64);

/**
 * @brief Pointer -> Location over a scenario and its includes (after merging, each value keeps
 * the file it came from). Lookups fall back to the nearest ancestor that is known.
 */
class SourceMap {
public:
    void setValue(const std::string& pointer, Location loc) { mValues[pointer] = std::move(loc); }
    void setKey(const std::string& pointer, Location loc) { mKeys[pointer] = std::move(loc); }

    /** @brief Where the value at `pointer` starts (or its nearest known ancestor). */
    Location value(std::string_view pointer) const;
    /** @brief Where the key of the member at `pointer` starts, else value(pointer). */
    Location key(std::string_view pointer) const;
    /** @brief The file a value came from (its own or an included one). */
    std::string file(std::string_view pointer) const { return value(pointer).file; }

private:
    std::map<std::string, Location, std::less<>> mValues;
    std::map<std::string, Location, std::less<>> mKeys;
};

}  // namespace kiosk::config
