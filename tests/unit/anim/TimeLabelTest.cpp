#include "runtime/anim/TimeLabel.h"
#include "runtime/core/TimeParse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <ctime>
#include <random>

namespace kiosk::anim {
namespace {

double iso(const char* text) {
    auto t = parseIso8601(text);
    EXPECT_TRUE(t.has_value()) << text;
    return t.value_or(0.0);
}

TEST(TimeLabel, IssueExample) {
    const double start = iso("2026-03-14T00:00:00Z");
    EXPECT_EQ(formatTimeLabel(iso("2026-03-14T06:40:00Z"), start, kDefaultTimeLabelFormat, 0),
              "2026-03-14 06:40 UTC  (T+6 h 40 min)");
    // Seconds are floored, never rounded up into the next minute.
    EXPECT_EQ(formatTimeLabel(iso("2026-03-14T06:40:59.9Z"), start, kDefaultTimeLabelFormat, 0),
              "2026-03-14 06:40 UTC  (T+6 h 40 min)");
    // A frame time computed as start + offset a hair below the minute still reads 6 h 40 min.
    EXPECT_EQ(formatElapsed(24000.0 - 1e-7), "T+6 h 40 min");
}

TEST(TimeLabel, FixedOffsets) {
    const double start = iso("2026-03-14T00:00:00Z");
    const double t = iso("2026-03-14T06:40:00Z");
    EXPECT_EQ(formatTimeLabel(t, start, "%Y-%m-%d %H:%M %Z %z", 120),
              "2026-03-14 08:40 UTC+02:00 +0200");
    // Crossing midnight backwards with a half-hour offset.
    EXPECT_EQ(formatTimeLabel(iso("2026-03-14T03:10:00Z"), start, "%F %R %Z %z", -330),
              "2026-03-13 21:40 UTC-05:30 -0530");
    TimeZone named{60, "CET"};
    EXPECT_EQ(formatTimeLabel(t, start, "%H:%M %Z", named), "07:40 CET");
}

TEST(TimeLabel, AllDirectives) {
    const double t = iso("2024-02-29T13:05:09Z");  // leap day, a Thursday
    const double start = iso("2024-02-27T12:00:00Z");
    EXPECT_EQ(formatTimeLabel(t, start, "%a %A %b %B %d %e %j %y %I %p %S %T %s %% %E", 0),
              "Thu Thursday Feb February 29 29 060 24 01 PM 09 13:05:09 1709211909 % "
              "T+2 d 1 h 5 min");
    EXPECT_EQ(formatTimeLabel(iso("2026-01-05T00:30:00Z"), 0, "%e|%I %p|%j", 0), " 5|12 AM|005");
    // Unknown directives are copied; a trailing % too.
    EXPECT_EQ(formatTimeLabel(t, start, "%Q %Y %", 0), "%Q 2024 %");
    EXPECT_EQ(formatTimeLabel(std::nan(""), start, "%Y", 0), "--");
}

TEST(TimeLabel, MatchesGmtimeOverManyDates) {
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<long long> dist(-2208988800LL, 7258118400LL);  // 1900 .. 2200
    for (int i = 0; i < 2000; ++i) {
        const long long s = dist(rng);
        const auto tt = static_cast<std::time_t>(s);
        std::tm tm{};
        gmtime_r(&tt, &tm);
        char expected[64];
        std::strftime(expected, sizeof expected, "%Y-%m-%d %H:%M:%S %j %a %b", &tm);
        EXPECT_EQ(formatTimeLabel(static_cast<double>(s), 0, "%Y-%m-%d %H:%M:%S %j %a %b", 0),
                  expected)
            << s;
    }
}

TEST(TimeLabel, ElapsedForms) {
    EXPECT_EQ(formatElapsed(0.0), "T+0 min");
    EXPECT_EQ(formatElapsed(0.4), "T+0 min");
    EXPECT_EQ(formatElapsed(45.0), "T+45 s");
    EXPECT_EQ(formatElapsed(60.0), "T+1 min");
    EXPECT_EQ(formatElapsed(3600.0), "T+1 h");
    EXPECT_EQ(formatElapsed(3659.0), "T+1 h");
    EXPECT_EQ(formatElapsed(-3900.0), "T-1 h 5 min");
    EXPECT_EQ(formatElapsed(-30.0), "T-30 s");
    EXPECT_EQ(formatElapsed(90000.0), "T+1 d 1 h");
    EXPECT_EQ(formatElapsed(86400.0 + 300.0), "T+1 d 5 min");
    EXPECT_EQ(formatElapsed(std::nan("")), "T+--");
}

TEST(TimeLabel, BufferFormTruncatesSafely) {
    char buf[8];
    const std::size_t n = formatTimeLabel(buf, sizeof buf, iso("2026-03-14T06:40:00Z"), 0,
                                          kDefaultTimeLabelFormat, TimeZone::utc());
    EXPECT_EQ(n, 7u);
    EXPECT_STREQ(buf, "2026-03");
    EXPECT_EQ(formatTimeLabel(buf, 0, 0.0, 0.0, "%Y", TimeZone::utc()), 0u);
}

struct ZoneCase {
    const char* text;
    int offset;
    const char* name;
};

class TimeZoneGood : public ::testing::TestWithParam<ZoneCase> {};

TEST_P(TimeZoneGood, Parses) {
    const auto& p = GetParam();
    auto r = parseTimeZone(p.text);
    ASSERT_TRUE(r.ok()) << p.text << ": " << r.diagnostics.format();
    EXPECT_EQ(r->offsetMinutes, p.offset);
    EXPECT_EQ(r->name, p.name);
}

INSTANTIATE_TEST_SUITE_P(
    Table, TimeZoneGood,
    ::testing::Values(ZoneCase{"UTC", 0, "UTC"}, ZoneCase{"Z", 0, "UTC"}, ZoneCase{"GMT", 0, "UTC"},
                      ZoneCase{"UTC+2", 120, "UTC+02:00"}, ZoneCase{"UTC+02:00", 120, "UTC+02:00"},
                      ZoneCase{"UTC-0530", -330, "UTC-05:30"}, ZoneCase{"+01:00", 60, "UTC+01:00"},
                      ZoneCase{"-3:30", -210, "UTC-03:30"}, ZoneCase{"UTC+14", 840, "UTC+14:00"},
                      ZoneCase{"UTC+00:00", 0, "UTC"}));

struct BadZone {
    const char* text;
    const char* code;
    const char* message;
};

class TimeZoneBad : public ::testing::TestWithParam<BadZone> {};

TEST_P(TimeZoneBad, Reports) {
    const auto& p = GetParam();
    auto r = parseTimeZone(p.text, "demo.json", "/overlays/timeLabel/timeZone");
    ASSERT_FALSE(r.ok()) << p.text;
    const Diagnostic* e = r.diagnostics.firstError();
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->code, p.code);
    EXPECT_EQ(e->where, "/overlays/timeLabel/timeZone");
    EXPECT_NE(e->message.find(p.message), std::string::npos) << e->message;
}

INSTANTIATE_TEST_SUITE_P(
    Table, TimeZoneBad,
    ::testing::Values(BadZone{"Europe/Berlin", "ANIM_TIMEZONE_UNSUPPORTED",
                              "\"Europe/Berlin\": named zones are not supported"},
                      BadZone{"CEST", "ANIM_TIMEZONE_INVALID",
                              "\"CEST\" is not UTC or a fixed offset"},
                      BadZone{"", "ANIM_TIMEZONE_INVALID", "is not UTC"},
                      BadZone{"UTC+15", "ANIM_TIMEZONE_INVALID", "\"UTC+15\""},
                      BadZone{"+01:75", "ANIM_TIMEZONE_INVALID", "\"+01:75\""},
                      BadZone{"+1:2", "ANIM_TIMEZONE_INVALID", "\"+1:2\""},
                      BadZone{"UTC+", "ANIM_TIMEZONE_INVALID", "\"UTC+\""},
                      BadZone{"+0100x", "ANIM_TIMEZONE_INVALID", "\"+0100x\""}));

TEST(TimeLabel, ValidateFormat) {
    EXPECT_TRUE(validateTimeFormat(kDefaultTimeLabelFormat).empty());
    EXPECT_TRUE(validateTimeFormat("%%Q").empty());
    auto d = validateTimeFormat("%Y %Q %k", "demo.json", "/overlays/timeLabel/format");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d.items()[0].code, "ANIM_TIME_FORMAT_UNKNOWN");
    EXPECT_EQ(d.items()[0].where, "/overlays/timeLabel/format");
    EXPECT_NE(d.items()[0].message.find("unknown directive %Q"), std::string::npos);
    EXPECT_NE(d.items()[1].message.find("unknown directive %k"), std::string::npos);
    d = validateTimeFormat("%H:%M %");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_NE(d.items()[0].message.find("lone '%'"), std::string::npos);
}

}  // namespace
}  // namespace kiosk::anim
