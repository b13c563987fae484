#pragma once

#include "config/MemoryBudgets.h"
#include "runtime/core/Result.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

// Kiosk files (docs/kiosk.md, config/schema/kiosk.schema.json): a playlist of scenarios with
// durations or loop counts, optional time-of-day windows and a transition, plus the service
// settings of one kiosk. Same message format as scenarios:
// `file:line:col: /json/pointer: what is wrong [CODE]`. Never throws; any thread.
namespace kiosk::config {

/** @brief Local time-of-day window [from, to) in seconds after midnight; wraps past midnight. */
struct TimeOfDayWindow {
    int fromSeconds = 0;
    int toSeconds = 0;
};

struct KioskEntry {
    std::filesystem::path scenario;         ///< resolved against the kiosk file's folder
    std::optional<double> durationSeconds;  ///< wall seconds on screen
    std::optional<int> loops;               ///< passes of the scenario's clock (default 1)
    std::optional<TimeOfDayWindow> window;  ///< only shown inside this window
    std::string pointer;                    ///< "/playlist/N" (messages)
};

enum class TransitionKind { Cut, Fade };

struct KioskFile {
    std::vector<KioskEntry> playlist;
    TransitionKind transition = TransitionKind::Cut;
    double transitionSeconds = 0;                    ///< Fade: through black, half out, half in
    std::optional<std::string> listen;               ///< "HOST:PORT" (play --listen wins)
    std::optional<std::filesystem::path> tokenFile;  ///< control token (play --token-file wins)
    /** @brief Per-kiosk cache budgets applied to every entry (terrain.cacheBytes / gpuBytes). */
    std::optional<std::int64_t> cacheBytes;
    std::optional<std::int64_t> gpuBytes;
    /** @brief LUT, mapping-array, font-atlas and SQLite page-cache budgets (with where set). */
    MemoryBudgets memory;
    std::filesystem::path file;
};

/**
 * @brief True when `file` is a JSON object with a "playlist" member (a kiosk file rather than a
 * scenario). Unreadable or malformed files answer false (the scenario reader then reports why).
 */
bool isKioskFile(const std::filesystem::path& file);

/**
 * @brief Read and check a kiosk file. The scenarios it names are not opened here: each entry is
 * validated when it is about to go on screen (a broken one is skipped, the rest plays).
 * Codes: KIOSK_FILE, KIOSK_PARSE, KIOSK_TYPE, KIOSK_UNKNOWN_PROPERTY, KIOSK_MISSING,
 * KIOSK_BAD_VALUE, KIOSK_CONFLICT.
 */
Result<KioskFile> readKioskFile(const std::filesystem::path& file);

/** @brief Accepted properties per object kind ("Kiosk" is the root; the rest are `$defs`). */
const std::map<std::string, std::vector<std::string>>& kioskProperties();

/** @brief "HH:MM" or "HH:MM:SS" (00:00 .. 24:00) -> seconds after midnight. */
std::optional<int> parseTimeOfDay(std::string_view text);

}  // namespace kiosk::config
