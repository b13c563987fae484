#include "runtime/core/Diagnostics.h"
#include "runtime/core/MessageText.h"
#include "runtime/core/TimeParse.h"

#include <gtest/gtest.h>

namespace kiosk {
namespace {

TEST(MessageText, ControlCharactersAreEscaped) {
    EXPECT_EQ(escapeForMessage("a\nb\tc\r", 100), "a\\nb\\tc\\r");
    EXPECT_EQ(escapeForMessage("\x1b[31m\x07\x7f", 100), "\\x1b[31m\\x07\\x7f");
    EXPECT_EQ(escapeForMessage("\xC2\x9B"
                               "2J",
                               100),
              "\\u{9b}2J");                                      // C1 CSI
    EXPECT_EQ(escapeForMessage("\xFF\xC3", 100), "\\xff\\xc3");  // not UTF-8
    EXPECT_EQ(escapeForMessage("h\xC3\xA9llo \xE2\x82\xAC", 100), "h\xC3\xA9llo \xE2\x82\xAC");
}

TEST(MessageText, LongTextIsCutAtACharacterWithAnEllipsis) {
    const std::string cut = escapeForMessage(std::string(1000, 'x'), 10);
    EXPECT_EQ(cut, std::string(10, 'x') + "\u2026");
    // Never in the middle of a UTF-8 sequence or an escape.
    EXPECT_EQ(escapeForMessage("abcd\xC3\xA9", 5), "abcd\u2026");
    EXPECT_EQ(escapeForMessage("abc\n", 4), "abc\u2026");
}

TEST(MessageText, DiagnosticFormatIsOneBoundedLine) {
    Diagnostic d{Severity::Error,
                 "CODE",
                 "f.json",
                 1,
                 2,
                 "/a\nb",
                 "bad \"x\nf.json:1:1: ok\"" + std::string(1 << 20, 'k'),
                 "hint\x1b"};
    const std::string line = d.format();
    EXPECT_EQ(line.find('\n'), std::string::npos);
    EXPECT_EQ(line.find('\x1b'), std::string::npos);
    EXPECT_LT(line.size(), 1400u);
    EXPECT_NE(line.find("f.json:1:2: /a\\nb: bad \"x\\nf.json:1:1: ok\""), std::string::npos);
    EXPECT_NE(line.find("(hint\\x1b) [CODE]"), std::string::npos);
}

TEST(TimeParseLimits, DatesMustExist) {
    EXPECT_FALSE(parseIso8601("2026-02-30T00:00:00Z"));
    EXPECT_FALSE(parseIso8601("2026-02-29T00:00:00Z"));
    EXPECT_TRUE(parseIso8601("2028-02-29T00:00:00Z"));
    EXPECT_FALSE(parseIso8601("1900-02-29T00:00:00Z"));
    EXPECT_TRUE(parseIso8601("2000-02-29T00:00:00Z"));
    EXPECT_FALSE(parseIso8601("2026-04-31T00:00:00Z"));
    EXPECT_TRUE(parseIso8601("2026-12-31T23:59:59Z"));
    EXPECT_FALSE(parseIso8601("2026-03-14T06:40:00+15:00"));
    EXPECT_TRUE(parseIso8601("2026-03-14T06:40:00+14:00"));
}

TEST(TimeParseLimits, OffsetsAreBounded) {
    EXPECT_FALSE(parseOffset("+" + std::string(400, '9') + "s"));
    EXPECT_FALSE(parseOffset("+1" + std::string(12, '0')));
    EXPECT_TRUE(parseOffset("+" + std::string(10, '9')));   // 317 years
    EXPECT_FALSE(parseOffset("+" + std::string(12, '9')));  // 31 700 years
    EXPECT_FALSE(parseOffset("+1001d" + std::string("365000d")));
    EXPECT_DOUBLE_EQ(*parseOffset("+999d"), 999.0 * 86400.0);
}

}  // namespace
}  // namespace kiosk
