#include "runtime/core/TimeParse.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kiosk {

TEST(TimeParseTest, Iso8601Utc) {
    EXPECT_EQ(parseIso8601("1970-01-01T00:00:00Z"), 0.0);
    EXPECT_EQ(parseIso8601("2026-03-14T06:40:00Z"), 1773470400.0);
    EXPECT_EQ(parseIso8601("2000-02-29T12:00:00Z"), 951825600.0);  // leap day
    EXPECT_EQ(parseIso8601("2026-03-14"), 1773446400.0);
    EXPECT_DOUBLE_EQ(*parseIso8601("1970-01-01T00:00:01.25Z"), 1.25);
    EXPECT_EQ(parseIso8601("2026-03-14T08:40:00+02:00"), 1773470400.0);
}

TEST(TimeParseTest, Iso8601Rejects) {
    for (const char* bad : {"", "2026", "2026-13-01T00:00:00Z", "2026-03-14T25:00:00Z",
                            "2026-03-14T06:40:00Zjunk", "14/03/2026", "2026-03-14T06"}) {
        EXPECT_FALSE(parseIso8601(bad).has_value()) << bad;
    }
}

TEST(TimeParseTest, Offsets) {
    EXPECT_EQ(parseOffset("+3600"), 3600.0);
    EXPECT_EQ(parseOffset("+1h30m"), 5400.0);
    EXPECT_EQ(parseOffset("+2d"), 172800.0);
    EXPECT_EQ(parseOffset("+90s"), 90.0);
    EXPECT_EQ(parseOffset("-10m"), -600.0);
    EXPECT_EQ(parseOffset("+1.5h"), 5400.0);
    for (const char* bad : {"3600", "+", "+1x", "+h", "+1h30"}) {
        EXPECT_FALSE(parseOffset(bad).has_value()) << bad;
    }
}

TEST(TimeParseTest, SpecResolvesAgainstStart) {
    auto off = parseTimeSpec("+1h");
    ASSERT_TRUE(off);
    EXPECT_TRUE(off->isOffset);
    EXPECT_EQ(off->resolve(1000.0), 4600.0);
    auto abs = parseTimeSpec("2026-03-14T06:40:00Z");
    ASSERT_TRUE(abs);
    EXPECT_FALSE(abs->isOffset);
    EXPECT_EQ(abs->resolve(1000.0), 1773470400.0);
    EXPECT_FALSE(parseTimeSpec("tomorrow"));
}

TEST(TimeParseTest, FormatRoundTrip) {
    EXPECT_EQ(formatIso8601(1773470400.0), "2026-03-14T06:40:00Z");
    EXPECT_EQ(parseIso8601(formatIso8601(951825600.0)), 951825600.0);
    EXPECT_EQ(formatIso8601(3e50), "(time out of range)");  // fuzz find: UB in the time_t cast
    EXPECT_EQ(formatIso8601(std::nan("")), "(time out of range)");
}

}  // namespace kiosk
