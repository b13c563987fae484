#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace kiosk {

/**
 * @brief A time given on the command line or in a scenario: either absolute (seconds since the
 * Unix epoch, UTC) or an offset from the scenario's start (docs/cli.md: `+3600`, `+1h30m`).
 */
struct TimeSpec {
    bool isOffset = false;
    double seconds = 0.0;  ///< epoch seconds (absolute) or offset seconds

    /** @brief Resolve against a scenario start given in epoch seconds. */
    double resolve(double startEpoch) const { return isOffset ? startEpoch + seconds : seconds; }
};

/** @brief Longest number in an offset: `+` followed by 400 digits is not a time anyone means. */
inline constexpr std::size_t kMaxOffsetDigits = 12;
/** @brief Largest offset magnitude accepted: 1000 years of 365.25 days. */
inline constexpr double kMaxOffsetSeconds = 1000.0 * 365.25 * 86400.0;

/**
 * @brief `2026-03-14T06:40:00Z` (also with fractional seconds or `+hh:mm`) -> epoch seconds.
 * The date must exist (`2026-02-30` is refused, not rolled over to March 2); zone offsets are
 * at most 14 hours.
 */
std::optional<double> parseIso8601(std::string_view text);
/**
 * @brief `+3600`, `+1h30m`, `+90s`, `+2d`, `-10m` -> seconds. Each number has at most
 * kMaxOffsetDigits characters and the total is at most kMaxOffsetSeconds.
 */
std::optional<double> parseOffset(std::string_view text);
/** @brief Either form. */
std::optional<TimeSpec> parseTimeSpec(std::string_view text);
/** @brief Epoch seconds -> `2026-03-14T06:40:00Z` (whole seconds, UTC); outside years 0..9999 or
 *  NaN: `(time out of range)`. */
std::string formatIso8601(double epochSeconds);

}  // namespace kiosk
