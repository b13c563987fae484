#pragma once

#include "runtime/core/Result.h"

#include <cstddef>
#include <string>
#include <string_view>

namespace kiosk::anim {

/**
 * @brief A fixed UTC offset with the name `%Z` prints. Only fixed offsets are supported: named
 * IANA zones (Europe/Berlin) with daylight-saving rules are rejected by `parseTimeZone` with
 * ANIM_TIMEZONE_UNSUPPORTED. A kiosk replaying an event is best labelled in one fixed zone
 * anyway (no repeated or skipped hour during replay); see docs/animation.md.
 */
struct TimeZone {
    int offsetMinutes = 0;     ///< east of UTC, within [-14 h, +14 h]
    std::string name = "UTC";  ///< printed by %Z: "UTC", "UTC+02:00", or a label the scenario gave

    static TimeZone utc() { return {}; }
    /** @brief Offset with the canonical name ("UTC" for 0, else "UTC+hh:mm"). */
    static TimeZone fixed(int offsetMinutes);
};

/**
 * @brief Parse a scenario's time zone: "UTC", "Z", "GMT", "UTC+2", "UTC+02:00", "UTC-0530",
 * "+01:00", "-03:30". Errors: ANIM_TIMEZONE_UNSUPPORTED (looks like an IANA name),
 * ANIM_TIMEZONE_INVALID (anything else, or beyond +-14 h).
 */
Result<TimeZone> parseTimeZone(std::string_view text, std::string_view file = {},
                               std::string_view where = {});

/** @brief `%Y-%m-%d %H:%M %Z  (%E)` -> `2026-03-14 06:40 UTC  (T+6 h 40 min)`. */
inline constexpr std::string_view kDefaultTimeLabelFormat = "%Y-%m-%d %H:%M %Z  (%E)";

/**
 * @brief Format a data time for the on-screen label.
 *
 * strftime-like directives, implemented here (no locale, no TZ environment, thread-safe):
 * %Y %y %m %d %e %H %I %p %M %S %j %a %A %b %B (English names) %F %T %R %s (epoch seconds)
 * %Z (zone name) %z (+hhmm) %% and our extension %E = time since `startEpoch`
 * (`T+6 h 40 min`, see formatElapsed). Unknown directives are copied literally (use
 * validateTimeFormat at load time to report them). Seconds are floored: 06:40:59.9 shows 06:40.
 * Non-finite `epoch` gives "--".
 */
std::string formatTimeLabel(double epoch, double startEpoch, std::string_view format,
                            int tzOffsetMinutes);
std::string formatTimeLabel(double epoch, double startEpoch, std::string_view format,
                            const TimeZone& zone);
/**
 * @brief Allocation-free form for the frame loop: writes at most `capacity - 1` characters and a
 * terminating NUL into `out` (truncating), returns the length written.
 */
std::size_t formatTimeLabel(char* out, std::size_t capacity, double epoch, double startEpoch,
                            std::string_view format, const TimeZone& zone) noexcept;

/**
 * @brief `T+6 h 40 min`, `T-1 d 2 h`, `T+45 s`, `T+0 min`: days, hours and minutes (zero parts
 * omitted, truncated towards zero), seconds only below one minute.
 */
std::string formatElapsed(double seconds);
/** @brief formatElapsed into `out` (NUL-terminated, truncated to capacity); no allocation. */
std::size_t formatElapsed(char* out, std::size_t capacity, double seconds);

/** @brief ANIM_TIME_FORMAT_UNKNOWN for each unknown `%x` directive, or a trailing lone `%`. */
Diagnostics validateTimeFormat(std::string_view format, std::string_view file = {},
                               std::string_view where = {});

}  // namespace kiosk::anim
