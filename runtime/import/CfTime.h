#pragma once

#include "runtime/core/Result.h"

#include <string>
#include <string_view>
#include <vector>

namespace kiosk::import {

/** @brief A parsed CF `units` attribute of a time axis: "<unit> since <reference date>". */
struct CfTimeUnits {
    double secondsPerUnit = 1.0;
    int year = 1970, month = 1, day = 1;  ///< reference date, in the axis' calendar
    double secondOfDay = 0.0;             ///< reference time of day (UTC after the zone offset)
};

enum class CfCalendar { Standard, ProlepticGregorian, NoLeap, AllLeap, Day360 };

/**
 * @brief Parse a CF time `units` string, e.g. "days since 1990-1-1 00:00:00",
 * "hours since 2001-10-16T13:00:00Z", "seconds since 1970-01-01 00:00:00 +10:00".
 * Units: seconds, minutes, hours, days (and their abbreviations); months/years are refused
 * (ambiguous in CF). Error code CF_TIME_UNITS naming the text.
 */
Result<CfTimeUnits> parseCfTimeUnits(std::string_view units);

/**
 * @brief Calendar attribute -> enum: standard, gregorian, proleptic_gregorian, noleap, 365_day,
 * all_leap, 366_day, 360_day (case-insensitive; empty = standard). Error CF_CALENDAR otherwise.
 */
Result<CfCalendar> parseCfCalendar(std::string_view calendar);

/**
 * @brief Convert time-axis values to UTC epoch seconds. Pure function.
 *
 * The offset is added to the reference date in the axis' own calendar, giving a date label
 * (Y-M-D h:m:s). Labels of the standard and proleptic Gregorian calendars are real dates. Labels of
 * model calendars map to the same label in the proleptic Gregorian calendar where the calendar's
 * month is not longer than the real one (so noleap dates keep their labels); a longer model month
 * (360_day February, all_leap February in a common year) is stretched linearly over the real
 * month, which keeps times strictly increasing. The standard calendar refuses reference dates
 * before 1582-10-15 (mixed Julian/Gregorian is not supported).
 */
Result<std::vector<double>> cfTimesToEpoch(const std::vector<double>& values,
                                           std::string_view units, std::string_view calendar);

}  // namespace kiosk::import
