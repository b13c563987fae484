#include "runtime/core/Strings.h"

#include <gtest/gtest.h>

#include "runtime/core/Diagnostics.h"
#include "runtime/core/TileId.h"

namespace kiosk {

TEST(StringsTest, EditDistance) {
    EXPECT_EQ(editDistance("depth", "depth"), 0u);
    EXPECT_EQ(editDistance("depht", "depth"), 2u);
    EXPECT_EQ(editDistance("", "abc"), 3u);
    EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
}

TEST(StringsTest, ClosestMatchSuggestsTyposOnly) {
    std::vector<std::string> names{"depth", "velocity", "elevation"};
    EXPECT_EQ(closestMatch("depht", names), "depth");
    EXPECT_EQ(closestMatch("elevaton", names), "elevation");
    EXPECT_FALSE(closestMatch("temperature", names).has_value());
}

TEST(StringsTest, ParseSize) {
    EXPECT_EQ(parseSize("1280x720"), (std::pair{1280, 720}));
    for (const char* bad : {"1280", "x720", "1280x", "0x10", "-5x5", "12a0x720", "99999x10"})
        EXPECT_FALSE(parseSize(bad).has_value()) << bad;
}

TEST(DiagnosticsTest, FormatNamesFileLinePointerAndHint) {
    Diagnostic d{Severity::Error, "SCENARIO_UNKNOWN_REFERENCE", "demo.json", 12, 5,
                 "/layers/2/transfer", "unknown transfer function \"depht\"",
                 "did you mean \"depth\"?"};
    EXPECT_EQ(d.format(),
              "demo.json:12:5: /layers/2/transfer: unknown transfer function \"depht\" "
              "(did you mean \"depth\"?) [SCENARIO_UNKNOWN_REFERENCE]");
}

TEST(DiagnosticsTest, ErrorsAndWarnings) {
    Diagnostics diags;
    diags.warning("W", "a", "", "careful");
    EXPECT_FALSE(diags.hasErrors());
    diags.error("E", "b", "/x", "broken");
    EXPECT_TRUE(diags.hasErrors());
    EXPECT_TRUE(diags.has("W"));
    ASSERT_NE(diags.firstError(), nullptr);
    EXPECT_EQ(diags.firstError()->code, "E");
    EXPECT_EQ(diags.format(), "a: warning: careful [W]\nb: /x: broken [E]\n");
}

TEST(TileIdTest, ParentChild) {
    TileId t{3, 5, 6};
    for (int q = 0; q < 4; ++q) EXPECT_EQ(t.child(q).parent(), t);
    EXPECT_EQ(t.child(3), (TileId{4, 11, 13}));
    EXPECT_NE(TileId({1, 0, 0}).packed(), TileId({0, 1, 0}).packed());
}

}  // namespace kiosk
