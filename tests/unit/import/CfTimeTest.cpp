#include "runtime/core/TimeParse.h"
#include "runtime/import/CfTime.h"

#include <gtest/gtest.h>

using namespace kiosk;
using namespace kiosk::import;

namespace {

struct Case {
    const char* units;
    const char* calendar;
    double value;
    const char* expected;  // ISO 8601 UTC
};

}  // namespace

TEST(CfTime, UnitsAndCalendarsTable) {
    const Case cases[] = {
        {"seconds since 1970-01-01 00:00:00", "standard", 86400, "1970-01-02T00:00:00Z"},
        {"hours since 2001-10-16T13:00:00Z", "gregorian", 6, "2001-10-16T19:00:00Z"},
        {"days since 1990-1-1", "proleptic_gregorian", 31, "1990-02-01T00:00:00Z"},
        {"days since 2000-01-01", "standard", 60, "2000-03-01T00:00:00Z"},  // 2000 is leap
        {"minutes since 2026-03-14 06:40", "standard", 90, "2026-03-14T08:10:00Z"},
        {"hours since 2020-01-01 00:00:00 +10:00", "standard", 0, "2019-12-31T14:00:00Z"},
        {"days since 0001-01-01", "proleptic_gregorian", 730119, "2000-01-01T00:00:00Z"},
        // noleap keeps labels: 2000-01-01 + 59 days is Mar 1 (no Feb 29).
        {"days since 2000-01-01", "noleap", 59, "2000-03-01T00:00:00Z"},
        {"days since 2000-01-01", "365_day", 365, "2001-01-01T00:00:00Z"},
        // all_leap: 2001 has a Feb 29 in the model; day 31+28 is Feb 29 -> stretched in Feb.
        {"days since 2001-01-01", "all_leap", 60, "2001-03-01T00:00:00Z"},
        {"days since 2001-01-01", "366_day", 366, "2002-01-01T00:00:00Z"},
        // 360_day: every month has 30 days; month starts map onto real month starts.
        {"days since 2000-01-01", "360_day", 30, "2000-02-01T00:00:00Z"},
        {"days since 2000-01-01", "360_day", 360, "2001-01-01T00:00:00Z"},
        {"days since 2000-01-01", "360_day", 75, "2000-03-16T00:00:00Z"},
        {"hours since 2000-01-01", "360_day", 24 * 45, "2000-02-15T12:00:00Z"},  // 15/30*29 d
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(std::string(c.units) + " / " + c.calendar);
        auto r = cfTimesToEpoch({c.value}, c.units, c.calendar);
        ASSERT_TRUE(r.ok()) << r.diagnostics.format();
        EXPECT_EQ(formatIso8601(r->front()), c.expected);
    }
}

TEST(CfTime, StrictlyIncreasingAcrossModelFebruary) {
    std::vector<double> days;
    for (int d = 0; d < 120; ++d) days.push_back(d);
    for (const char* cal : {"360_day", "all_leap", "noleap"}) {
        auto r = cfTimesToEpoch(days, "days since 2001-01-01", cal);
        ASSERT_TRUE(r.ok());
        for (std::size_t i = 1; i < r->size(); ++i)
            EXPECT_GT((*r)[i], (*r)[i - 1]) << cal << " " << i;
    }
}

struct BadCase {
    const char* units;
    const char* calendar;
    const char* code;
    const char* message;
};

TEST(CfTime, BadUnitsTable) {
    const BadCase cases[] = {
        {"days", "standard", "CF_TIME_UNITS", "expected '<unit> since <date>'"},
        {"fortnights since 2000-01-01", "standard", "CF_TIME_UNITS",
         "unknown time unit 'fortnights'"},
        {"months since 2000-01-01", "standard", "CF_TIME_UNITS", "ambiguous"},
        {"days since yesterday", "standard", "CF_TIME_UNITS", "reference date is not Y-M-D"},
        {"days since 2000-13-01", "standard", "CF_TIME_UNITS", "out of range"},
        {"days since 2000-01-01", "julian_ish", "CF_CALENDAR", "unsupported calendar 'julian_ish'"},
        {"days since 1500-01-01", "standard", "CF_CALENDAR", "before 1582-10-15"},
        {"days since 2000-02-30", "noleap", "CF_TIME_UNITS", "does not exist in this calendar"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(std::string(c.units) + " / " + c.calendar);
        auto r = cfTimesToEpoch({0.0}, c.units, c.calendar);
        ASSERT_FALSE(r.ok());
        EXPECT_EQ(r.diagnostics.firstError()->code, c.code);
        EXPECT_NE(r.diagnostics.firstError()->message.find(c.message), std::string::npos)
            << r.diagnostics.format();
    }
}
