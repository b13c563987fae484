#include "runtime/wall/FollowerSync.h"
#include "runtime/wall/SwapBarrier.h"
#include "runtime/wall/SyncMessages.h"

#include <gtest/gtest.h>

namespace kiosk::wall {
namespace {

FrameState state(std::uint64_t frame, double t = 100.0) {
    FrameState s;
    s.frame = frame;
    s.dataTime = t;
    s.stepTime = t - 1;
    s.camera = {glm::dvec3(1, 2, 3), 45.0, -30.0, 900.0};
    s.scenarioHash = 0x1234567890abcdefull;
    s.scenarioId = "flood.json";
    s.rate = 60;
    s.seekSerial = 7;
    s.paused = true;
    s.chapter = 1;
    return s;
}

Ready ready(std::uint32_t screen, std::uint64_t frame, bool step = true) {
    Ready r;
    r.screen = screen;
    r.frame = frame;
    r.resident = true;
    r.stepResident = step;
    return r;
}

TEST(SyncMessagesTest, RoundTripAndRejectTruncated) {
    const FrameState s = state(42, 1.5e9);
    auto bytes = encode(s);
    EXPECT_EQ(messageType(bytes), MessageType::State);
    auto back = decodeState(bytes);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->frame, 42u);
    EXPECT_EQ(back->dataTime, 1.5e9);
    EXPECT_EQ(back->camera.range, 900.0);
    EXPECT_EQ(back->scenarioHash, s.scenarioHash);
    EXPECT_EQ(back->scenarioId, "flood.json");
    EXPECT_EQ(back->seekSerial, 7u);
    EXPECT_TRUE(back->paused);
    EXPECT_EQ(back->chapter, 1);
    for (std::size_t n = 0; n < bytes.size(); ++n)
        EXPECT_FALSE(decodeState(std::span(bytes).first(n))) << n;
    bytes.push_back(0);
    EXPECT_FALSE(decodeState(bytes));
    auto rb = encode(ready(3, 9, false));
    EXPECT_FALSE(decodeState(rb));  // wrong type
    auto r = decodeReady(rb);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->screen, 3u);
    EXPECT_TRUE(r->resident);
    EXPECT_FALSE(r->stepResident);
    auto rel = decodeRelease(encode(Release{5, true, 3}));
    ASSERT_TRUE(rel);
    EXPECT_EQ(rel->frame, 5u);
    EXPECT_TRUE(rel->byDeadline);
    EXPECT_EQ(messageType(encodeStop()), MessageType::Stop);
    EXPECT_FALSE(messageType(std::vector<std::uint8_t>{9, 1}));
}

TEST(SwapBarrierTest, ReleasesWhenAllReadyElseAtTheDeadline) {
    SwapBarrier b({1, 2, 3}, 0.1);
    b.begin(1, 10.0);
    EXPECT_FALSE(b.releasable(10.0));
    b.leaderReady(true);
    b.onReady(ready(1, 1));
    b.onReady(ready(2, 1));
    EXPECT_FALSE(b.releasable(10.05));
    b.onReady(ready(3, 1));
    EXPECT_TRUE(b.releasable(10.05));
    Release r = b.release();
    EXPECT_EQ(r.frame, 1u);
    EXPECT_FALSE(r.byDeadline);
    EXPECT_EQ(r.readyNodes, 4u);
    EXPECT_TRUE(b.stepResident());

    // Screen 2 dies: frame 2 waits until the deadline, then drops it.
    b.begin(2, 11.0);
    b.leaderReady(true);
    b.onReady(ready(1, 2));
    b.onReady(ready(3, 2));
    EXPECT_FALSE(b.releasable(11.099));
    EXPECT_TRUE(b.releasable(11.1));
    r = b.release();
    EXPECT_TRUE(r.byDeadline);
    EXPECT_EQ(b.lastDropped(), std::vector<std::uint32_t>{2});
    EXPECT_FALSE(b.isMember(2));
    // ... and is not waited for afterwards: the wall keeps swapping at full rate.
    b.begin(3, 12.0);
    b.leaderReady(true);
    b.onReady(ready(1, 3));
    b.onReady(ready(3, 3));
    EXPECT_TRUE(b.releasable(12.0));
    b.release();
    EXPECT_EQ(b.members(), 2u);
}

TEST(SwapBarrierTest, DroppedNodeRejoins) {
    SwapBarrier b({1, 2}, 0.1);
    b.begin(1, 0.0);
    b.leaderReady(true);
    b.onReady(ready(1, 1));
    b.release();  // 2 dropped
    ASSERT_FALSE(b.isMember(2));
    // A stale report (it restarted and drew an old state): member again from the next frame.
    b.begin(2, 1.0);
    b.onReady(ready(2, 1));
    EXPECT_FALSE(b.isMember(2));
    b.leaderReady(true);
    b.onReady(ready(1, 2));
    EXPECT_TRUE(b.releasable(1.0));
    b.release();
    b.begin(3, 2.0);
    EXPECT_TRUE(b.isMember(2));
    b.leaderReady(true);
    b.onReady(ready(1, 3));
    EXPECT_FALSE(b.releasable(2.0));  // waits for the rejoined node
    // A report for the open frame counts at once.
    b.onReady(ready(2, 3));
    EXPECT_TRUE(b.releasable(2.0));
    // Unknown screens are ignored.
    b.onReady(ready(99, 3));
    EXPECT_EQ(b.release().readyNodes, 3u);
}

TEST(SwapBarrierTest, StepAdvancesOnlyWhenEveryNodeHasIt) {
    SwapBarrier b({1, 2}, 0.1);
    b.begin(1, 0.0);
    b.leaderReady(true);
    b.onReady(ready(1, 1, true));
    b.onReady(ready(2, 1, false));
    b.release();
    EXPECT_FALSE(b.stepResident());
    b.begin(2, 1.0);
    b.leaderReady(false);
    b.onReady(ready(1, 2, true));
    b.onReady(ready(2, 2, true));
    b.release();
    EXPECT_FALSE(b.stepResident());
    // A node dropped at the deadline does not hold the step back.
    b.begin(3, 2.0);
    b.leaderReady(true);
    b.onReady(ready(1, 3, true));
    b.release();
    EXPECT_TRUE(b.stepResident());
}

TEST(FollowerSyncTest, DrawReportSwap) {
    FollowerSync f(2, 1.0);
    EXPECT_FALSE(f.takeStateToDraw());
    f.onState(state(1), 0.0);
    auto s = f.takeStateToDraw();
    ASSERT_TRUE(s);
    EXPECT_EQ(s->frame, 1u);
    // Not resident yet: no report; then resident: one report.
    EXPECT_FALSE(f.drawn(false, false, 7));
    auto r = f.drawn(true, true, 7);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->screen, 2u);
    EXPECT_EQ(r->frame, 1u);
    EXPECT_FALSE(f.drawn(true, true, 7));
    // The leader republishes while waiting for joiners: nothing new.
    f.onState(state(1), 0.01);
    EXPECT_FALSE(f.takeStateToDraw());
    EXPECT_FALSE(f.swapDue());
    f.onRelease(Release{1, false, 3});
    ASSERT_TRUE(f.swapDue());
    EXPECT_EQ(f.swapped(), 1u);
    EXPECT_FALSE(f.swapDue());
}

TEST(FollowerSyncTest, BehindSkipsToTheNewestState) {
    FollowerSync f(1, 1.0);
    f.onState(state(5), 0.0);
    f.onRelease(Release{5, true, 1});
    f.onState(state(6), 0.0);
    f.onRelease(Release{6, true, 1});
    f.onState(state(7), 0.0);
    auto s = f.takeStateToDraw();
    ASSERT_TRUE(s);
    EXPECT_EQ(s->frame, 7u);    // rejoins at the current state
    EXPECT_FALSE(f.swapDue());  // releases of frames it never drew do not swap
    f.onRelease(Release{7, false, 2});
    EXPECT_TRUE(f.swapDue());
}

TEST(FollowerSyncTest, SilentLeaderKeepsTheLastFrame) {
    FollowerSync f(1, 0.5);
    EXPECT_FALSE(f.leaderSilent(100.0));  // never heard of one: not "gone"
    f.onState(state(1), 10.0);
    f.takeStateToDraw();
    f.onRelease(Release{1, false, 2});
    f.swapped();
    EXPECT_FALSE(f.leaderSilent(10.4));
    EXPECT_TRUE(f.leaderSilent(10.6));
    EXPECT_FALSE(f.takeStateToDraw());
    EXPECT_EQ(f.shownFrame(), 1u);
    f.onStop();
    EXPECT_TRUE(f.stopped());
}

}  // namespace
}  // namespace kiosk::wall
