#include "runtime/anim/TimeLabel.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace kiosk::anim {
namespace {

constexpr int kMaxOffsetMinutes = 14 * 60;
constexpr const char* kWeekdays[] = {"Sunday",   "Monday", "Tuesday", "Wednesday",
                                     "Thursday", "Friday", "Saturday"};
constexpr const char* kMonths[] = {"January",   "February", "March",    "April",
                                   "May",       "June",     "July",     "August",
                                   "September", "October",  "November", "December"};

struct Civil {
    long long year;
    int month, day, hour, minute, second, yday, wday;
};

// Howard Hinnant's civil_from_days: no gmtime, so no TZ environment and no 2038 limit.
Civil civilFromSeconds(long long s) {
    long long days = s / 86400;
    long long rem = s % 86400;
    if (rem < 0) {
        rem += 86400;
        --days;
    }
    Civil c{};
    c.hour = static_cast<int>(rem / 3600);
    c.minute = static_cast<int>(rem % 3600 / 60);
    c.second = static_cast<int>(rem % 60);
    c.wday = static_cast<int>(((days % 7) + 11) % 7);  // 1970-01-01 was a Thursday (4)
    const long long z = days + 719468;
    const long long era = (z >= 0 ? z : z - 146096) / 146097;
    const long long doe = z - era * 146097;
    const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const long long mp = (5 * doy + 2) / 153;
    c.day = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
    c.month = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
    c.year = yoe + era * 400 + (c.month <= 2 ? 1 : 0);
    const bool leap = (c.year % 4 == 0 && c.year % 100 != 0) || c.year % 400 == 0;
    static constexpr int kCum[] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
    c.yday = kCum[c.month - 1] + c.day - 1 + (leap && c.month > 2 ? 1 : 0);
    return c;
}

// Bounded writer: silently truncates, always leaves room for the NUL.
struct Writer {
    char* out;
    std::size_t cap;
    std::size_t len = 0;
    void put(char ch) {
        if (len + 1 < cap) out[len++] = ch;
    }
    void put(const char* s) {
        while (*s) put(*s++);
    }
    void putf(const char* fmt, long long v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, fmt, v);
        put(buf);
    }
};

bool knownDirective(char c) {
    return std::strchr("YymdeHIpMSjaAbBFTRsZzE%", c) != nullptr && c != '\0';
}

void writeElapsed(Writer& w, double seconds) {
    if (!std::isfinite(seconds)) {
        w.put("T+--");
        return;
    }
    // Frame times are often computed (start + offset); a few ulps below a whole minute must not
    // read as the minute before.
    const double a = std::fabs(seconds) + 1e-6;
    const bool negative = seconds < 0.0 && a >= 1.0;
    w.put(negative ? "T-" : "T+");
    const auto total = static_cast<long long>(std::floor(std::min(a, 9.0e15)));
    if (total < 60) {
        if (total == 0) {
            w.put("0 min");
        } else {
            w.putf("%lld s", total);
        }
        return;
    }
    const long long minutesTotal = total / 60;
    const long long d = minutesTotal / 1440, h = minutesTotal / 60 % 24, m = minutesTotal % 60;
    bool first = true;
    auto part = [&](long long v, const char* unit) {
        if (v == 0) return;
        if (!first) w.put(' ');
        w.putf("%lld", v);
        w.put(' ');
        w.put(unit);
        first = false;
    };
    part(d, "d");
    part(h, "h");
    part(m, "min");
}

std::string offsetName(int minutes) {
    if (minutes == 0) return "UTC";
    char buf[16];
    const int a = minutes < 0 ? -minutes : minutes;
    std::snprintf(buf, sizeof buf, "UTC%c%02d:%02d", minutes < 0 ? '-' : '+', a / 60, a % 60);
    return buf;
}

}  // namespace

TimeZone TimeZone::fixed(int offsetMinutes) {
    return {offsetMinutes, offsetName(offsetMinutes)};
}

Result<TimeZone> parseTimeZone(std::string_view text, std::string_view file,
                               std::string_view where) {
    Diagnostics d;
    const std::string f(file), w(where);
    std::string_view s = text;
    if (s == "UTC" || s == "Z" || s == "GMT" || s == "Etc/UTC") return TimeZone::utc();
    if (s.substr(0, 3) == "UTC" || s.substr(0, 3) == "GMT") s.remove_prefix(3);
    auto invalid = [&] {
        d.error("ANIM_TIMEZONE_INVALID", f, w,
                "time zone \"" + std::string(text) +
                    "\" is not UTC or a fixed offset such as UTC+02:00")
            .hint = "use \"UTC\", \"UTC+02:00\" or \"-05:30\"";
        return d;
    };
    if (s.empty() || (s[0] != '+' && s[0] != '-')) {
        if (text.find('/') != std::string_view::npos) {
            d.error("ANIM_TIMEZONE_UNSUPPORTED", f, w,
                    "time zone \"" + std::string(text) +
                        "\": named zones are not supported, only fixed UTC offsets")
                .hint = "give the offset in effect during the event, e.g. \"UTC+01:00\"";
            return d;
        }
        return invalid();
    }
    const int sign = s[0] == '-' ? -1 : 1;
    s.remove_prefix(1);
    int digits[4];
    int nd = 0;
    bool colon = false;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const char c = s[i];
        if (c == ':' && !colon && (nd == 1 || nd == 2)) {
            // "+1:30" means 01:30: normalise to two hour digits.
            if (nd == 1) {
                digits[1] = digits[0];
                digits[0] = 0;
                nd = 2;
            }
            colon = true;
            continue;
        }
        if (!std::isdigit(static_cast<unsigned char>(c)) || nd == 4) return invalid();
        digits[nd++] = c - '0';
    }
    int hours = 0, minutes = 0;
    if (nd == 1 && !colon) {
        hours = digits[0];
    } else if (nd == 2 && !colon) {
        hours = digits[0] * 10 + digits[1];
    } else if (nd == 4) {
        hours = digits[0] * 10 + digits[1];
        minutes = digits[2] * 10 + digits[3];
    } else {
        return invalid();
    }
    if (minutes >= 60) return invalid();
    const int total = sign * (hours * 60 + minutes);
    if (total < -kMaxOffsetMinutes || total > kMaxOffsetMinutes) return invalid();
    return TimeZone::fixed(total);
}

std::size_t formatTimeLabel(char* out, std::size_t capacity, double epoch, double startEpoch,
                            std::string_view format, const TimeZone& zone) noexcept {
    if (capacity == 0 || out == nullptr) return 0;
    Writer w{out, capacity};
    if (!std::isfinite(epoch)) {
        w.put("--");
        out[w.len] = '\0';
        return w.len;
    }
    const double clamped = std::fmax(-9.0e15, std::fmin(9.0e15, epoch));
    const auto local = static_cast<long long>(std::floor(clamped)) +
                       static_cast<long long>(zone.offsetMinutes) * 60;
    const Civil c = civilFromSeconds(local);
    for (std::size_t i = 0; i < format.size(); ++i) {
        const char ch = format[i];
        if (ch != '%' || i + 1 == format.size()) {
            w.put(ch);
            continue;
        }
        const char dir = format[++i];
        switch (dir) {
            case 'Y':
                w.putf("%04lld", c.year);
                break;
            case 'y':
                w.putf("%02lld", ((c.year % 100) + 100) % 100);
                break;
            case 'm':
                w.putf("%02lld", c.month);
                break;
            case 'd':
                w.putf("%02lld", c.day);
                break;
            case 'e':
                w.putf("%2lld", c.day);
                break;
            case 'H':
                w.putf("%02lld", c.hour);
                break;
            case 'I':
                w.putf("%02lld", (c.hour + 11) % 12 + 1);
                break;
            case 'p':
                w.put(c.hour < 12 ? "AM" : "PM");
                break;
            case 'M':
                w.putf("%02lld", c.minute);
                break;
            case 'S':
                w.putf("%02lld", c.second);
                break;
            case 'j':
                w.putf("%03lld", c.yday + 1);
                break;
            case 'a': {
                char abbr[4] = {kWeekdays[c.wday][0], kWeekdays[c.wday][1], kWeekdays[c.wday][2],
                                '\0'};
                w.put(abbr);
                break;
            }
            case 'A':
                w.put(kWeekdays[c.wday]);
                break;
            case 'b': {
                const char* mn = kMonths[c.month - 1];
                char abbr[4] = {mn[0], mn[1], mn[2], '\0'};
                w.put(abbr);
                break;
            }
            case 'B':
                w.put(kMonths[c.month - 1]);
                break;
            case 'F':
                w.putf("%04lld", c.year);
                w.putf("-%02lld", c.month);
                w.putf("-%02lld", c.day);
                break;
            case 'T':
                w.putf("%02lld", c.hour);
                w.putf(":%02lld", c.minute);
                w.putf(":%02lld", c.second);
                break;
            case 'R':
                w.putf("%02lld", c.hour);
                w.putf(":%02lld", c.minute);
                break;
            case 's':
                w.putf("%lld", static_cast<long long>(std::floor(clamped)));
                break;
            case 'Z':
                w.put(zone.name.c_str());
                break;
            case 'z': {
                const int a = zone.offsetMinutes < 0 ? -zone.offsetMinutes : zone.offsetMinutes;
                w.put(zone.offsetMinutes < 0 ? '-' : '+');
                w.putf("%02lld", a / 60);
                w.putf("%02lld", a % 60);
                break;
            }
            case 'E':
                writeElapsed(w, epoch - startEpoch);
                break;
            case '%':
                w.put('%');
                break;
            default:
                w.put('%');
                w.put(dir);
                break;
        }
    }
    out[w.len] = '\0';
    return w.len;
}

std::string formatTimeLabel(double epoch, double startEpoch, std::string_view format,
                            const TimeZone& zone) {
    // Labels are short; grow only for unusually long format strings.
    std::string s(std::max<std::size_t>(128, format.size() * 8 + 64), '\0');
    s.resize(formatTimeLabel(s.data(), s.size(), epoch, startEpoch, format, zone));
    return s;
}

std::string formatTimeLabel(double epoch, double startEpoch, std::string_view format,
                            int tzOffsetMinutes) {
    return formatTimeLabel(epoch, startEpoch, format, TimeZone::fixed(tzOffsetMinutes));
}

std::string formatElapsed(double seconds) {
    char buf[64];
    return std::string(buf, formatElapsed(buf, sizeof buf, seconds));
}

std::size_t formatElapsed(char* out, std::size_t capacity, double seconds) {
    if (capacity == 0) return 0;
    Writer w{out, capacity};
    writeElapsed(w, seconds);
    out[std::min(w.len, capacity - 1)] = '\0';
    return std::min(w.len, capacity - 1);
}

Diagnostics validateTimeFormat(std::string_view format, std::string_view file,
                               std::string_view where) {
    Diagnostics d;
    for (std::size_t i = 0; i < format.size(); ++i) {
        if (format[i] != '%') continue;
        if (i + 1 == format.size()) {
            d.error("ANIM_TIME_FORMAT_UNKNOWN", std::string(file), std::string(where),
                    "time format \"" + std::string(format) + "\" ends with a lone '%'")
                .hint = "write %% for a literal percent sign";
            break;
        }
        const char dir = format[++i];
        if (!knownDirective(dir))
            d.error("ANIM_TIME_FORMAT_UNKNOWN", std::string(file), std::string(where),
                    "time format \"" + std::string(format) + "\": unknown directive %" +
                        std::string(1, dir))
                .hint =
                "supported: %Y %y %m %d %e %H %I %p %M %S %j %a %A %b %B %F %T %R %s "
                "%Z %z %E %%";
    }
    return d;
}

}  // namespace kiosk::anim
