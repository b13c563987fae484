#include "runtime/service/Watchdog.h"

#include <gtest/gtest.h>

namespace kiosk::service {
namespace {

TEST(WatchdogTest, ReadyOnceAfterTheFirstFrame) {
    WatchdogPacer p(0);
    EXPECT_TRUE(p.frameCompleted(0.0).ready);
    EXPECT_FALSE(p.frameCompleted(0.1).ready);
    EXPECT_FALSE(p.frameCompleted(0.2).watchdog);  // watchdog off: never a ping
}

TEST(WatchdogTest, PingsAtHalfTheIntervalOnlyWhenFramesComplete) {
    WatchdogPacer p(2'000'000);  // WatchdogSec=2
    EXPECT_DOUBLE_EQ(p.pingInterval(), 1.0);
    EXPECT_TRUE(p.frameCompleted(10.0).watchdog);
    EXPECT_FALSE(p.frameCompleted(10.5).watchdog);
    EXPECT_TRUE(p.frameCompleted(11.0).watchdog);
    // A 30 s stall: no call, no ping; the next frame pings at once.
    EXPECT_TRUE(p.frameCompleted(41.0).watchdog);
}

TEST(WatchdogTest, HoldingKeepsPingingButNeverSendsReady) {
    WatchdogPacer p(2'000'000);
    const WatchdogPacer::Due first = p.holding(10.0);  // a follower before its first frame
    EXPECT_FALSE(first.ready);
    EXPECT_TRUE(first.watchdog);
    EXPECT_FALSE(p.holding(10.5).watchdog);
    EXPECT_TRUE(p.holding(11.0).watchdog);
    EXPECT_TRUE(p.frameCompleted(11.2).ready);  // READY still waits for a real frame
    EXPECT_FALSE(p.holding(11.4).ready);
}

TEST(WatchdogTest, StatusAtMostOncePerSecond) {
    WatchdogPacer p(0);
    EXPECT_TRUE(p.frameCompleted(0.0).status);
    EXPECT_FALSE(p.frameCompleted(0.5).status);
    EXPECT_TRUE(p.frameCompleted(1.0).status);
}

}  // namespace
}  // namespace kiosk::service
