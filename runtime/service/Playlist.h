#pragma once

#include <cstdint>
#include <optional>
#include <vector>

// Playlist scheduling (pure): which entry plays next given local time-of-day windows and
// entries known to be broken, when the current one is done, and the fade of a transition.
namespace kiosk::service {

struct PlaylistRule {
    double durationSeconds = 0;  ///< > 0: wall seconds on screen
    int loops = 0;               ///< > 0: passes of the scenario clock
    bool hasWindow = false;
    int windowFrom = 0, windowTo = 0;  ///< seconds after local midnight, [from, to), may wrap
};

/** @brief Inside the rule's window at `secondOfDay` (always true without a window). */
bool inWindow(const PlaylistRule& rule, int secondOfDay) noexcept;

/**
 * @brief The next playable entry starting at `from` (included when `includeFrom`) and moving
 * by `step` (+1 or -1, wrapping): inside its window and not `broken`. -1 when none is.
 */
int pickEntry(const std::vector<PlaylistRule>& rules, int from, int step, int secondOfDay,
              const std::vector<bool>& broken, bool includeFrom);

struct EntryProgress {
    double wallSeconds = 0;   ///< on screen so far
    std::uint64_t loops = 0;  ///< clock wraps so far (ScenarioClock::loops)
    bool clockAtEnd = false;  ///< a clamped clock reached its end
};

/**
 * @brief The entry is done: its duration elapsed, or its loop count completed (a clamped clock
 * at its end counts as one more pass), or its window closed.
 */
bool entryFinished(const PlaylistRule& rule, const EntryProgress& p, int secondOfDay) noexcept;

/**
 * @brief Fade-through-black alpha (0: picture, 1: black) `sinceStart` seconds into an entry
 * whose end is `untilEnd` seconds away (nullopt: unknown, loop-count entries): fading in over the
 * first half of `fadeSeconds`, out over the last half.
 */
float fadeAlpha(double sinceStart, std::optional<double> untilEnd, double fadeSeconds) noexcept;

/** @brief Local seconds after midnight for a Unix time (the machine's time zone). */
int localSecondOfDay(double epochSeconds) noexcept;

}  // namespace kiosk::service
