#include "runtime/import/CfTime.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

namespace kiosk::import {

namespace {

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool gregorianLeap(long long y) {
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

int gregorianMonthDays(long long y, int m) {
    static const int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return m == 2 && gregorianLeap(y) ? 29 : kDays[m - 1];
}

// Howard Hinnant's days_from_civil: days since 1970-01-01 in the proleptic Gregorian calendar.
long long daysFromCivil(long long y, int m, int d) {
    y -= m <= 2;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const long long yoe = y - era * 400;
    const long long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const long long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

int calMonthDays(CfCalendar cal, long long y, int m) {
    switch (cal) {
        case CfCalendar::Day360:
            return 30;
        case CfCalendar::NoLeap:
            return gregorianMonthDays(1, m);  // year 1 is common
        case CfCalendar::AllLeap:
            return gregorianMonthDays(4, m);  // year 4 is leap
        default:
            return gregorianMonthDays(y, m);
    }
}

int calYearDays(CfCalendar cal) {
    return cal == CfCalendar::Day360 ? 360 : cal == CfCalendar::NoLeap ? 365 : 366;
}

// Day count of a label in a fixed-length model calendar (day 0 = year 0, Jan 1).
long long modelDays(CfCalendar cal, long long y, int m, int d) {
    long long days = y * calYearDays(cal);
    for (int i = 1; i < m; ++i) days += calMonthDays(cal, y, i);
    return days + d - 1;
}

void modelLabel(CfCalendar cal, long long days, long long& y, int& m, int& d) {
    const long long len = calYearDays(cal);
    y = days >= 0 ? days / len : -((-days + len - 1) / len);
    long long rest = days - y * len;
    m = 1;
    while (rest >= calMonthDays(cal, y, m)) rest -= calMonthDays(cal, y, m++);
    d = int(rest) + 1;
}

}  // namespace

Result<CfTimeUnits> parseCfTimeUnits(std::string_view text) {
    Diagnostics diag;
    const std::string s = lower(text);
    const auto since = s.find(" since ");
    auto fail = [&](const std::string& why) {
        diag.error("CF_TIME_UNITS", "", "units",
                   "cannot parse time units '" + std::string(text) + "': " + why);
        return Result<CfTimeUnits>(diag);
    };
    if (since == std::string::npos) return fail("expected '<unit> since <date>'");
    std::string unit = s.substr(0, since);
    while (!unit.empty() && std::isspace(static_cast<unsigned char>(unit.front())))
        unit.erase(0, 1);
    CfTimeUnits u;
    if (unit == "seconds" || unit == "second" || unit == "secs" || unit == "sec" || unit == "s")
        u.secondsPerUnit = 1;
    else if (unit == "minutes" || unit == "minute" || unit == "mins" || unit == "min")
        u.secondsPerUnit = 60;
    else if (unit == "hours" || unit == "hour" || unit == "hrs" || unit == "hr" || unit == "h")
        u.secondsPerUnit = 3600;
    else if (unit == "days" || unit == "day" || unit == "d")
        u.secondsPerUnit = 86400;
    else if (unit == "months" || unit == "month" || unit == "years" || unit == "year")
        return fail("calendar months and years are ambiguous in CF; use days or hours");
    else
        return fail("unknown time unit '" + unit + "'");

    std::string date = s.substr(since + 7);
    long long y = 0;
    int mo = 0, d = 0, h = 0, mi = 0, consumed = 0;
    double sec = 0;
    if (std::sscanf(date.c_str(), "%lld-%d-%d%n", &y, &mo, &d, &consumed) != 3)
        return fail("reference date is not Y-M-D");
    std::string rest = date.substr(std::size_t(consumed));
    if (!rest.empty() && (rest[0] == 't' || rest[0] == ' ')) {
        std::size_t i = 0;
        while (i < rest.size() && (rest[i] == 't' || rest[i] == ' ')) ++i;
        int n = 0;
        if (i < rest.size() && std::isdigit(static_cast<unsigned char>(rest[i]))) {
            const std::string t = rest.substr(i);
            if (std::sscanf(t.c_str(), "%d:%d%n", &h, &mi, &n) == 2) {
                int n2 = 0;
                if (t.size() > std::size_t(n) && t[std::size_t(n)] == ':' &&
                    std::sscanf(t.c_str() + n, ":%lf%n", &sec, &n2) == 1)
                    n += n2;
                rest = t.substr(std::size_t(n));
            } else if (std::sscanf(t.c_str(), "%d%n", &h, &n) == 1) {
                rest = t.substr(std::size_t(n));
            } else {
                return fail("bad time of day");
            }
        }
    }
    // Zone: Z, UTC, +hh:mm, -hh, +hhmm.
    while (!rest.empty() && rest[0] == ' ') rest.erase(0, 1);
    double zone = 0;
    if (rest == "z" || rest == "utc" || rest == "gmt" || rest.empty()) {
    } else if (rest[0] == '+' || rest[0] == '-') {
        int zh = 0, zm = 0;
        const int sign = rest[0] == '-' ? -1 : 1;
        if (rest.find(':') != std::string::npos) {
            if (std::sscanf(rest.c_str() + 1, "%d:%d", &zh, &zm) < 1) return fail("bad zone");
        } else {
            int v = 0;
            if (std::sscanf(rest.c_str() + 1, "%d", &v) != 1) return fail("bad zone");
            if (rest.size() > 3) {
                zh = v / 100;
                zm = v % 100;
            } else {
                zh = v;
            }
        }
        zone = sign * (zh * 3600.0 + zm * 60.0);
    } else {
        return fail("unexpected text '" + rest + "' after the date");
    }
    if (mo < 1 || mo > 12 || d < 1 || d > 31 || h < 0 || h > 24 || mi < 0 || mi > 59 || sec < 0 ||
        sec >= 61)
        return fail("reference date out of range");
    u.year = int(y);
    u.month = mo;
    u.day = d;
    u.secondOfDay = h * 3600.0 + mi * 60.0 + sec - zone;
    return u;
}

Result<CfCalendar> parseCfCalendar(std::string_view calendar) {
    const std::string c = lower(calendar);
    if (c.empty() || c == "standard" || c == "gregorian") return CfCalendar::Standard;
    if (c == "proleptic_gregorian") return CfCalendar::ProlepticGregorian;
    if (c == "noleap" || c == "365_day") return CfCalendar::NoLeap;
    if (c == "all_leap" || c == "366_day") return CfCalendar::AllLeap;
    if (c == "360_day") return CfCalendar::Day360;
    Diagnostics d;
    d.error("CF_CALENDAR", "", "calendar",
            "unsupported calendar '" + std::string(calendar) +
                "' (standard, gregorian, proleptic_gregorian, noleap, 365_day, all_leap, "
                "366_day, 360_day)");
    return d;
}

Result<std::vector<double>> cfTimesToEpoch(const std::vector<double>& values,
                                           std::string_view units, std::string_view calendar) {
    auto u = parseCfTimeUnits(units);
    if (!u) return u.diagnostics;
    auto cal = parseCfCalendar(calendar);
    if (!cal) return cal.diagnostics;
    Diagnostics d;
    const bool real = *cal == CfCalendar::Standard || *cal == CfCalendar::ProlepticGregorian;
    if (*cal == CfCalendar::Standard &&
        (u->year < 1582 ||
         (u->year == 1582 && (u->month < 10 || (u->month == 10 && u->day < 15))))) {
        d.error("CF_CALENDAR", "", "units",
                "reference date before 1582-10-15 in the mixed Julian/Gregorian calendar is not "
                "supported (use proleptic_gregorian)");
        return d;
    }
    if (!real && u->day > calMonthDays(*cal, u->year, u->month)) {
        d.error("CF_TIME_UNITS", "", "units", "reference date does not exist in this calendar");
        return d;
    }
    std::vector<double> out;
    out.reserve(values.size());
    for (double v : values) {
        if (!std::isfinite(v)) {
            d.error("CF_TIME_VALUE", "", "time", "time value is not finite");
            return d;
        }
        const double offset = v * u->secondsPerUnit + u->secondOfDay;
        if (real) {
            out.push_back(double(daysFromCivil(u->year, u->month, u->day)) * 86400.0 + offset);
            continue;
        }
        // Walk in the model calendar to a label, then place the label on the real time line.
        const double totalDays =
            double(modelDays(*cal, u->year, u->month, u->day)) + offset / 86400.0;
        const double dayFloor = std::floor(totalDays);
        const double secOfDay = (totalDays - dayFloor) * 86400.0;
        long long y = 0;
        int m = 0, dd = 0;
        modelLabel(*cal, (long long)dayFloor, y, m, dd);
        const int calDays = calMonthDays(*cal, y, m), realDays = gregorianMonthDays(y, m);
        const double monthStart = double(daysFromCivil(y, m, 1)) * 86400.0;
        const double inMonth = (dd - 1) * 86400.0 + secOfDay;
        if (calDays <= realDays)
            out.push_back(monthStart + inMonth);
        else
            out.push_back(monthStart + inMonth * double(realDays) / double(calDays));
    }
    return out;
}

}  // namespace kiosk::import
