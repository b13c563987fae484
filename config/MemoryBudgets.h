#pragma once

#include <cstdint>
#include <string>

// Memory budgets a kiosk file sets for every entry it plays (docs/kiosk.md, `budgets`): the
// caches beside the tile cache that would otherwise grow with what a scenario asks for. Never
// read from a scenario file. Where each was set travels with it, so a refusal names the kiosk
// file, line and JSON pointer.
namespace kiosk::config {

struct MemoryBudget {
    std::int64_t bytes = 0;  ///< 0: not set (the default applies)
    std::string file;        ///< kiosk file that set it
    int line = 0, column = 0;
    std::string pointer;  ///< "/budgets/lutBytes"
    bool set() const noexcept { return bytes > 0; }
};

struct MemoryBudgets {
    MemoryBudget luts;             ///< transfer-function LUT textures (layers, mappings, legends)
    MemoryBudget mappings;         ///< projective-mapping data arrays (CPU copy + GPU array)
    MemoryBudget fontAtlas;        ///< overlay font atlas (CPU copy + GPU texture)
    MemoryBudget sqlitePageCache;  ///< SQLite page cache of each store connection
};

}  // namespace kiosk::config
