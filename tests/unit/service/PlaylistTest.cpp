#include "runtime/service/Playlist.h"

#include <gtest/gtest.h>

namespace kiosk::service {
namespace {

PlaylistRule window(int fromH, int toH) {
    PlaylistRule r;
    r.durationSeconds = 60;
    r.hasWindow = true;
    r.windowFrom = fromH * 3600;
    r.windowTo = toH * 3600;
    return r;
}

TEST(PlaylistTest, WindowsIncludeFromExcludeToAndWrapPastMidnight) {
    const PlaylistRule day = window(6, 22), night = window(22, 6);
    EXPECT_TRUE(inWindow(day, 6 * 3600));
    EXPECT_FALSE(inWindow(day, 22 * 3600));
    EXPECT_FALSE(inWindow(day, 3 * 3600));
    EXPECT_TRUE(inWindow(night, 23 * 3600));
    EXPECT_TRUE(inWindow(night, 2 * 3600));
    EXPECT_FALSE(inWindow(night, 12 * 3600));
    EXPECT_TRUE(inWindow(PlaylistRule{}, 12 * 3600));
}

TEST(PlaylistTest, PickSkipsBrokenAndOutOfWindowEntriesAndWraps) {
    std::vector<PlaylistRule> rules = {PlaylistRule{}, PlaylistRule{}, window(22, 6),
                                       PlaylistRule{}};
    const int noon = 12 * 3600;
    std::vector<bool> broken = {false, true, false, false};
    EXPECT_EQ(pickEntry(rules, 0, 1, noon, broken, true), 0);
    EXPECT_EQ(pickEntry(rules, 0, 1, noon, broken, false), 3);  // 1 broken, 2 out of window
    EXPECT_EQ(pickEntry(rules, 3, 1, noon, broken, false), 0);  // wraps
    EXPECT_EQ(pickEntry(rules, 0, -1, noon, broken, false), 3);
    EXPECT_EQ(pickEntry(rules, 3, -1, noon, broken, false), 0);
    EXPECT_EQ(pickEntry(rules, 0, 1, 23 * 3600, broken, false), 2);  // night entry now eligible
    // Only the current entry is playable: it comes round again.
    EXPECT_EQ(pickEntry(rules, 0, 1, noon, {false, true, true, true}, false), 0);
    EXPECT_EQ(pickEntry(rules, 0, 1, noon, {true, true, true, true}, true), -1);
    EXPECT_EQ(pickEntry({}, 0, 1, noon, {}, true), -1);
}

TEST(PlaylistTest, EntryFinishesOnDurationLoopsOrWindowEnd) {
    PlaylistRule d;
    d.durationSeconds = 30;
    EXPECT_FALSE(entryFinished(d, {29.9, 5, true}, 0));
    EXPECT_TRUE(entryFinished(d, {30.0, 0, false}, 0));
    PlaylistRule l;
    l.loops = 2;
    EXPECT_FALSE(entryFinished(l, {1000, 1, false}, 0));
    EXPECT_TRUE(entryFinished(l, {1, 2, false}, 0));
    EXPECT_TRUE(entryFinished(l, {1, 1, true}, 0));  // a clamped clock at its end: last pass
    const PlaylistRule w = window(6, 22);
    EXPECT_FALSE(entryFinished(w, {1, 0, false}, 21 * 3600));
    EXPECT_TRUE(entryFinished(w, {1, 0, false}, 22 * 3600));
}

TEST(PlaylistTest, FadeThroughBlack) {
    EXPECT_FLOAT_EQ(fadeAlpha(0.0, 10.0, 0.0), 0.0f);  // cut
    EXPECT_FLOAT_EQ(fadeAlpha(0.0, 10.0, 2.0), 1.0f);  // entry starts black
    EXPECT_FLOAT_EQ(fadeAlpha(0.5, 10.0, 2.0), 0.5f);
    EXPECT_FLOAT_EQ(fadeAlpha(5.0, 5.0, 2.0), 0.0f);
    EXPECT_FLOAT_EQ(fadeAlpha(9.5, 0.5, 2.0), 0.5f);  // fading out before the end
    EXPECT_FLOAT_EQ(fadeAlpha(9.5, std::nullopt, 2.0), 0.0f);
}

TEST(PlaylistTest, LocalSecondOfDayIsInRange) {
    const int s = localSecondOfDay(1773446400.0);
    EXPECT_GE(s, 0);
    EXPECT_LT(s, 86400);
}

}  // namespace
}  // namespace kiosk::service
