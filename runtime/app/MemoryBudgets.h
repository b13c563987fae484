#pragma once

#include "config/Scenario.h"
#include "runtime/core/Diagnostics.h"

#include <cstdint>
#include <string>

// The budgets of the caches beside the tile cache (docs/kiosk.md `budgets`): transfer-function
// LUTs, projective-mapping arrays, the overlay font atlas and SQLite's page cache. A kiosk file
// sets them for every entry; otherwise the defaults below apply. LUTs and mapping arrays grow
// with what a scenario asks for, so a scenario needing more than its budget is refused before
// anything is allocated (a playlist entry is skipped, a hot reload keeps the last good picture);
// the font atlas is degraded to the largest text size that fits.
namespace kiosk::app {

/** @brief The budgets in effect (bytes). */
struct EffectiveBudgets {
    std::uint64_t lutBytes = 0;
    std::uint64_t mappingBytes = 0;
    std::uint64_t fontAtlasBytes = 0;
    std::uint64_t sqlitePageCacheBytes = 0;  ///< per store connection
};

struct BudgetDefaults {
    /** @brief 256 layer LUTs; a scenario's 12 layers, 64 mapping LUT rows and a legend need 0.6. */
    static constexpr std::uint64_t kLutBytes = std::uint64_t(1) << 20;
    /** @brief The text sizes play uses (up to 40 px) fit several times over. */
    static constexpr std::uint64_t kFontAtlasBytes = std::uint64_t(1) << 20;
    /** @brief Mapping arrays: an eighth of physical memory, at most what 64 data layers take. */
    static std::uint64_t mappingBytes();
};

EffectiveBudgets effectiveBudgets(const config::MemoryBudgets& set);

/** @brief The most a scenario's LUTs and mapping arrays take (nothing opened, no GL). */
struct MemoryNeeds {
    int luts = 0;  ///< layer LUTs, mapping LUT rows and a legend's own LUT
    std::uint64_t lutBytes = 0;
    int mappingLayers = 0;  ///< array layers: images (one per file), scalar data, routes (2)
    std::uint64_t mappingBytes = 0;
};
MemoryNeeds memoryNeeds(const config::Scenario& scenario);

/**
 * @brief Errors BUDGET_LUTS / BUDGET_MAPPINGS when the scenario needs more than its budget: one
 * line naming the kiosk file, line and pointer of the budget (or the scenario, for a default),
 * the figure needed and the budget.
 */
Diagnostics checkMemoryBudgets(const config::Scenario& scenario);

/**
 * @brief The largest text size <= `wantedPx` whose atlas (CPU copy + GPU texture, 2 bytes per
 * texel) fits `budgetBytes`; `atlasBytes` gets its size, `wantedBytes` the size `wantedPx`
 * needs. 0 when not even kMinFontPx fits or the
 * font cannot be read.
 */
int fontPxWithin(const std::string& fontPath, int wantedPx, std::uint64_t budgetBytes,
                 std::uint64_t& atlasBytes, std::uint64_t* wantedBytes = nullptr);
inline constexpr int kMinFontPx = 6;

/** @brief "1.5 MiB" style figure for messages. */
std::string bytesText(std::uint64_t bytes);

}  // namespace kiosk::app
