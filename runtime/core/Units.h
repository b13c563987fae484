#pragma once

#include <optional>
#include <string>
#include <string_view>

// Units of data values as files state them (CF `units`, a GeoTIFF band's unit type, a scenario's
// transfer function): free text, compared by meaning for the few spellings data sets really use.
namespace kiosk {

/**
 * @brief Units text with surrounding blanks removed, or nullopt with `why` set when it cannot be
 * shown in a legend or `info` line (control characters, longer than 64 bytes).
 */
std::optional<std::string> cleanUnits(std::string_view text, std::string* why = nullptr);

/**
 * @brief One spelling per meaning for comparison: "metres", "meter" -> "m"; "mm h-1", "mm/hr",
 * "mm h**-1" -> "mm/h"; "m s-1" -> "m/s"; "degrees_Celsius" -> "degC". Unknown words are kept
 * as written (units are case-sensitive: "Mm" is not "mm").
 */
std::string canonicalUnits(std::string_view text);

/** @brief Same units by canonicalUnits (an empty side is "not stated" and never the same). */
bool sameUnits(std::string_view a, std::string_view b);

}  // namespace kiosk
