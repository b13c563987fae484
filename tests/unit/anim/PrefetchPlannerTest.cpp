#include "runtime/anim/PrefetchPlanner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace kiosk::anim {
namespace {

std::vector<double> regularFrames(std::size_t n, double t0, double dt) {
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = t0 + dt * static_cast<double>(i);
    return v;
}

std::vector<std::size_t> frameList(const PrefetchPlan& p) {
    std::vector<std::size_t> v;
    for (const auto& it : p.items) v.push_back(it.frame);
    return v;
}

bool contains(const PrefetchPlan& p, std::size_t f) {
    const auto v = frameList(p);
    return std::find(v.begin(), v.end(), f) != v.end();
}

PrefetchInput baseInput(const std::vector<double>& frames) {
    PrefetchInput in;
    in.frameTimes = frames;
    in.range = RangeMode::Clamp;
    in.rangeStart = frames.front();
    in.rangeEnd = frames.back();
    in.margin = 2;
    return in;
}

// Independent check of the deadline rule: every frame the playhead will need within one load
// time (walking forward, no wrap) must be planned; otherwise it cannot arrive in time.
void expectDeadlinesCovered(const PrefetchInput& in, const PrefetchPlan& p) {
    const auto& f = in.frameTimes;
    for (std::size_t j = 1; j < f.size(); ++j) {
        // Data mode forward: frame j joins the bracket when t reaches f[j-1].
        const double deadline = (f[j - 1] - in.playhead) / in.rate;
        if (f[j] > in.playhead && deadline <= in.meanLoadSeconds) {
            EXPECT_TRUE(contains(p, j)) << "frame " << j << " due in " << deadline << " s";
        }
    }
}

TEST(PrefetchPlanner, DepthCoversTheLoadTimeAtTheRate) {
    const auto frames = regularFrames(100, 0.0, 60.0);  // one frame a minute
    auto in = baseInput(frames);
    in.playhead = 630.0;  // between frames 10 and 11
    in.rate = 60.0;       // one frame per wall second
    in.meanLoadSeconds = 2.5;
    const PrefetchPlan p = PrefetchPlanner().plan(in);
    // ceil(2.5 * 60 / 60) = 3, + margin 2.
    EXPECT_EQ(p.depth, 5);
    EXPECT_EQ(frameList(p), (std::vector<std::size_t>{10, 11, 12, 13, 14, 15, 16}));
    EXPECT_EQ(p.items[0].deadlineSeconds, 0.0);
    EXPECT_EQ(p.items[1].deadlineSeconds, 0.0);
    EXPECT_DOUBLE_EQ(p.items[2].deadlineSeconds, 0.5);  // frame 12 joins at t = 660
    EXPECT_DOUBLE_EQ(p.items[3].deadlineSeconds, 1.5);
    // 2.5 frames are shown per load time: one loader working frame after frame falls behind
    // (latency is covered by the depth, throughput is not).
    EXPECT_FALSE(p.sustainable);
    EXPECT_FALSE(p.wrapped);
    expectDeadlinesCovered(in, p);

    // Ten times faster and loads ten times quicker: same depth, deadlines scale.
    in.rate = 600.0;
    in.meanLoadSeconds = 0.25;
    const PrefetchPlan fast = PrefetchPlanner().plan(in);
    EXPECT_EQ(fast.depth, 3 + 2);
    EXPECT_DOUBLE_EQ(fast.items[2].deadlineSeconds, 0.05);
    expectDeadlinesCovered(in, fast);
    // Ten times faster again with the same load time: the look-ahead grows with the rate.
    in.rate = 6000.0;
    const PrefetchPlan faster = PrefetchPlanner().plan(in);
    EXPECT_EQ(faster.depth, 25 + 2);
    EXPECT_EQ(faster.items.size(), 2u + 27u);
    expectDeadlinesCovered(in, faster);
    // Loads quicker than frames are consumed: sustainable.
    in.rate = 60.0;
    in.meanLoadSeconds = 0.5;
    const PrefetchPlan slow = PrefetchPlanner().plan(in);
    EXPECT_TRUE(slow.sustainable);
    EXPECT_EQ(slow.depth, 1 + 2);
    expectDeadlinesCovered(in, slow);
}

TEST(PrefetchPlanner, DenseIrregularFramesAheadAreAllCovered) {
    // Mean interval is large, but the frames just ahead are 5 s apart.
    std::vector<double> frames = {0, 100, 105, 110, 115, 120, 125, 130, 1000, 2000, 3000};
    auto in = baseInput(frames);
    in.playhead = 101.0;
    in.rate = 10.0;
    in.meanLoadSeconds = 2.0;  // 20 data seconds: frames 2 .. 5 are due within one load
    const PrefetchPlan p = PrefetchPlanner().plan(in);
    expectDeadlinesCovered(in, p);
    for (std::size_t f = 1; f <= 6; ++f) EXPECT_TRUE(contains(p, f)) << f;
    EXPECT_GE(p.depth, 4 + in.margin);
    // Deadlines never decrease along the list (it is sorted by urgency).
    for (std::size_t i = 1; i < p.items.size(); ++i)
        EXPECT_LE(p.items[i - 1].deadlineSeconds, p.items[i].deadlineSeconds);
}

TEST(PrefetchPlanner, WrapsToTheLoopStartBeforeTheLoopEnds) {
    const auto frames = regularFrames(20, 1000.0, 10.0);  // 1000 .. 1190
    auto in = baseInput(frames);
    in.range = RangeMode::Loop;
    in.rangeStart = 1025.0;  // between frames 2 and 3
    in.rangeEnd = 1150.0;    // frame 15
    in.playhead = 1141.0;    // (14, 15)
    in.rate = 10.0;
    in.meanLoadSeconds = 2.0;
    const PrefetchPlan p = PrefetchPlanner().plan(in);
    EXPECT_TRUE(p.wrapped);
    const auto list = frameList(p);
    ASSERT_GE(list.size(), 5u);
    EXPECT_EQ(list[0], 14u);
    EXPECT_EQ(list[1], 15u);
    // Nothing past the loop end; the loop start's bracket (2, 3) comes next.
    EXPECT_EQ(list[2], 2u);
    EXPECT_EQ(list[3], 3u);
    EXPECT_EQ(list[4], 4u);
    for (auto f : list) EXPECT_LE(f, 15u);
    // Frame 2 is needed the moment the loop wraps: 0.9 s from now.
    EXPECT_NEAR(p.items[2].deadlineSeconds, 0.9, 1e-9);
    // Frame 4 joins when t passes 1030 after the wrap: 0.9 + 0.5 s.
    EXPECT_NEAR(p.items[4].deadlineSeconds, 1.4, 1e-9);

    // Clamp mode with the same playhead stops at the end.
    in.range = RangeMode::Clamp;
    const PrefetchPlan clamp = PrefetchPlanner().plan(in);
    EXPECT_FALSE(clamp.wrapped);
    EXPECT_EQ(frameList(clamp), (std::vector<std::size_t>{14, 15}));
}

TEST(PrefetchPlanner, NegativeRateWalksBackAndWrapsToTheEnd) {
    const auto frames = regularFrames(10, 0.0, 10.0);
    auto in = baseInput(frames);
    in.range = RangeMode::Loop;
    in.playhead = 15.0;  // (1, 2)
    in.rate = -10.0;
    in.meanLoadSeconds = 1.0;
    in.margin = 3;
    const PrefetchPlan p = PrefetchPlanner().plan(in);
    EXPECT_EQ(frameList(p), (std::vector<std::size_t>{2, 1, 0, 9, 8, 7}));
    EXPECT_TRUE(p.wrapped);
    EXPECT_DOUBLE_EQ(p.items[2].deadlineSeconds, 0.5);  // frame 0 joins when t < 10
}

TEST(PrefetchPlanner, RespectsTheByteBudget) {
    const auto frames = regularFrames(50, 0.0, 1.0);
    auto in = baseInput(frames);
    in.playhead = 10.5;
    in.rate = 20.0;
    in.meanLoadSeconds = 0.04;
    in.margin = 6;  // wants 2 + 7 frames
    in.bytesPerFrame = 8u << 20;
    in.byteBudget = 5 * (8u << 20) + 123;  // room for five frames
    PrefetchPlan p = PrefetchPlanner().plan(in);
    EXPECT_EQ(p.items.size(), 5u);
    EXPECT_TRUE(p.budgetLimited);
    EXPECT_EQ(frameList(p), (std::vector<std::size_t>{10, 11, 12, 13, 14}));
    in.byteBudget = 1;  // less than the current pair: the pair is still listed
    p = PrefetchPlanner().plan(in);
    EXPECT_EQ(frameList(p), (std::vector<std::size_t>{10, 11}));
    EXPECT_TRUE(p.budgetLimited);
    in.byteBudget = 0;  // no limit
    in.maxDepth = 3;
    p = PrefetchPlanner().plan(in);
    EXPECT_EQ(p.items.size(), 5u);
    EXPECT_FALSE(p.budgetLimited);
}

TEST(PrefetchPlanner, PausedPlansNeighboursForStepping) {
    const auto frames = regularFrames(10, 0.0, 10.0);
    auto in = baseInput(frames);
    in.playhead = 40.0;  // exactly frame 4: one frame needed
    in.rate = 0.0;
    in.margin = 2;
    const PrefetchPlan p = PrefetchPlanner().plan(in);
    EXPECT_EQ(frameList(p), (std::vector<std::size_t>{4, 5, 3, 6, 2}));
    EXPECT_TRUE(std::isinf(p.items.back().deadlineSeconds));
}

TEST(PrefetchPlanner, StepModePlansSingleFrames) {
    const auto frames = regularFrames(10, 0.0, 10.0);
    auto in = baseInput(frames);
    in.mode = Interpolation::None;
    in.playhead = 41.0;
    in.rate = 10.0;
    in.meanLoadSeconds = 1.0;
    in.margin = 1;
    const PrefetchPlan p = PrefetchPlanner().plan(in);
    EXPECT_EQ(frameList(p), (std::vector<std::size_t>{4, 5, 6}));
    EXPECT_DOUBLE_EQ(p.items[1].deadlineSeconds, 0.9);  // frame 5 shown when t reaches 50
}

TEST(PrefetchPlanner, SeekBumpsTheGeneration) {
    ClockSettings cs;
    cs.start = 0;
    cs.end = 100;
    auto clock = *ScenarioClock::create(cs);
    PrefetchPlanner planner;
    const auto frames = regularFrames(10, 0.0, 10.0);
    auto in = baseInput(frames);
    EXPECT_FALSE(planner.syncSeekSerial(clock.seekSerial()));
    const auto g0 = planner.plan(in).generation;
    clock.advance(1.0);
    EXPECT_FALSE(planner.syncSeekSerial(clock.seekSerial()));  // playing is not seeking
    clock.seek(70.0);
    EXPECT_TRUE(planner.syncSeekSerial(clock.seekSerial()));
    EXPECT_FALSE(planner.syncSeekSerial(clock.seekSerial()));
    const auto g1 = planner.plan(in).generation;
    EXPECT_EQ(g1, g0 + 1);
    planner.notifySeek();
    EXPECT_EQ(planner.plan(in).generation, g0 + 2);
}

TEST(PrefetchPlanner, DegenerateInputs) {
    PrefetchInput in;
    EXPECT_TRUE(PrefetchPlanner().plan(in).items.empty());
    const auto frames = regularFrames(3, 0.0, 10.0);
    in = baseInput(frames);
    in.playhead = std::nan("");
    EXPECT_TRUE(PrefetchPlanner().plan(in).items.empty());
    in.playhead = 5.0;
    in.rate = std::nan("");  // treated as paused
    in.meanLoadSeconds = -3.0;
    const auto p = PrefetchPlanner().plan(in);
    EXPECT_EQ(frameList(p), (std::vector<std::size_t>{0, 1, 2}));
}

TEST(LoadTimeEstimator, FollowsMeasurements) {
    LoadTimeEstimator e(0.05, 0.5);
    EXPECT_DOUBLE_EQ(e.mean(), 0.05);
    e.record(0.2);
    EXPECT_DOUBLE_EQ(e.mean(), 0.2);  // the first sample replaces the guess
    e.record(0.4);
    EXPECT_DOUBLE_EQ(e.mean(), 0.3);
    e.record(std::nan(""));
    e.record(-1.0);
    EXPECT_DOUBLE_EQ(e.mean(), 0.3);
    EXPECT_EQ(e.samples(), 2u);
}

}  // namespace
}  // namespace kiosk::anim
