#include "runtime/core/TimeParse.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <ctime>

namespace kiosk {
namespace {

// Days since 1970-01-01 for a proleptic Gregorian date (Howard Hinnant's algorithm); avoids
// timegm's dependence on the TZ environment.
long long daysFromCivil(long long y, unsigned m, unsigned d) {
    y -= m <= 2;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const auto yoe = static_cast<unsigned>(y - era * 400);
    const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + static_cast<long long>(doe) - 719468;
}

bool readInt(std::string_view s, std::size_t& pos, int digits, int& out) {
    if (pos + std::size_t(digits) > s.size()) return false;
    out = 0;
    for (int i = 0; i < digits; ++i) {
        char c = s[pos + std::size_t(i)];
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
        out = out * 10 + (c - '0');
    }
    pos += std::size_t(digits);
    return true;
}

bool isLeap(long long y) {
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

// Days in a month of the proleptic Gregorian calendar: `2026-02-30` is refused, not rolled over.
int daysInMonth(long long y, int m) {
    static const int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return m == 2 && isLeap(y) ? 29 : kDays[m - 1];
}

bool expect(std::string_view s, std::size_t& pos, char c) {
    if (pos < s.size() && s[pos] == c) {
        ++pos;
        return true;
    }
    return false;
}

}  // namespace

std::optional<double> parseIso8601(std::string_view s) {
    std::size_t p = 0;
    int year, month, day, hour = 0, minute = 0, second = 0;
    if (!readInt(s, p, 4, year) || !expect(s, p, '-') || !readInt(s, p, 2, month) ||
        !expect(s, p, '-') || !readInt(s, p, 2, day))
        return std::nullopt;
    if (month < 1 || month > 12 || day < 1 || day > daysInMonth(year, month)) return std::nullopt;
    double frac = 0.0;
    if (p < s.size() && (s[p] == 'T' || s[p] == ' ')) {
        ++p;
        if (!readInt(s, p, 2, hour) || !expect(s, p, ':') || !readInt(s, p, 2, minute))
            return std::nullopt;
        if (expect(s, p, ':')) {
            if (!readInt(s, p, 2, second)) return std::nullopt;
            if (expect(s, p, '.')) {
                double scale = 0.1;
                std::size_t start = p;
                while (p < s.size() && std::isdigit(static_cast<unsigned char>(s[p]))) {
                    frac += (s[p] - '0') * scale;
                    scale /= 10.0;
                    ++p;
                }
                if (p == start) return std::nullopt;
            }
        }
        if (hour > 23 || minute > 59 || second > 60) return std::nullopt;
    }
    int tzSeconds = 0;
    if (p < s.size()) {
        if (s[p] == 'Z') {
            ++p;
        } else if (s[p] == '+' || s[p] == '-') {
            int sign = s[p] == '-' ? -1 : 1;
            ++p;
            int th, tm = 0;
            if (!readInt(s, p, 2, th)) return std::nullopt;
            expect(s, p, ':');
            if (p < s.size() && !readInt(s, p, 2, tm)) return std::nullopt;
            if (th > 14 || tm > 59) return std::nullopt;  // real zones span -12:00..+14:00
            tzSeconds = sign * (th * 3600 + tm * 60);
        }
    }
    if (p != s.size()) return std::nullopt;
    const long long days = daysFromCivil(year, unsigned(month), unsigned(day));
    return double(days * 86400 + hour * 3600 + minute * 60 + second - tzSeconds) + frac;
}

std::optional<double> parseOffset(std::string_view s) {
    if (s.empty() || (s[0] != '+' && s[0] != '-')) return std::nullopt;
    const double sign = s[0] == '-' ? -1.0 : 1.0;
    std::size_t p = 1;
    if (p == s.size()) return std::nullopt;
    double total = 0.0;
    bool sawUnit = false, sawNumber = false;
    while (p < s.size()) {
        std::size_t start = p;
        double value = 0.0;
        while (p < s.size() && (std::isdigit(static_cast<unsigned char>(s[p])) || s[p] == '.'))
            ++p;
        if (p == start || p - start > kMaxOffsetDigits) return std::nullopt;
        if (std::sscanf(std::string(s.substr(start, p - start)).c_str(), "%lf", &value) != 1)
            return std::nullopt;
        sawNumber = true;
        if (p == s.size()) {
            if (sawUnit) return std::nullopt;  // "1h30" is ambiguous; ask for "1h30m"
            total += value;
            break;
        }
        double unit;
        switch (s[p]) {
            case 'd': unit = 86400; break;
            case 'h': unit = 3600; break;
            case 'm': unit = 60; break;
            case 's': unit = 1; break;
            default: return std::nullopt;
        }
        ++p;
        sawUnit = true;
        total += value * unit;
    }
    if (!sawNumber || !(total <= kMaxOffsetSeconds)) return std::nullopt;
    return sign * total;
}

std::optional<TimeSpec> parseTimeSpec(std::string_view text) {
    if (auto off = parseOffset(text)) return TimeSpec{true, *off};
    if (auto abs = parseIso8601(text)) return TimeSpec{false, *abs};
    return std::nullopt;
}

std::string formatIso8601(double epochSeconds) {
    // Years 0000..9999 only: a hostile number (3e50 in a times CSV) must not reach the time_t
    // conversion, which is undefined past its range.
    if (!(epochSeconds >= -62167219200.0 && epochSeconds < 253402300800.0))
        return "(time out of range)";
    const auto t = static_cast<std::time_t>(std::floor(epochSeconds));
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

}  // namespace kiosk
