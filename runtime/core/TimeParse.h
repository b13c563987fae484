#pragma once

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

/** @brief `2026-03-14T06:40:00Z` (also with fractional seconds or `+hh:mm`) -> epoch seconds. */
std::optional<double> parseIso8601(std::string_view text);
/** @brief `+3600`, `+1h30m`, `+90s`, `+2d`, `-10m` -> seconds. */
std::optional<double> parseOffset(std::string_view text);
/** @brief Either form. */
std::optional<TimeSpec> parseTimeSpec(std::string_view text);
/** @brief Epoch seconds -> `2026-03-14T06:40:00Z` (whole seconds, UTC). */
std::string formatIso8601(double epochSeconds);

}  // namespace kiosk
