#include "runtime/anim/ScenarioClock.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace kiosk::anim {
namespace {

constexpr double kT0 = 1773446400.0;  // 2026-03-14T00:00:00Z

ScenarioClock makeClock(double start, double end, double rate, RangeMode mode,
                        std::optional<double> initial = std::nullopt) {
    ClockSettings s;
    s.start = start;
    s.end = end;
    s.rate = rate;
    s.range = mode;
    s.initial = initial;
    auto r = ScenarioClock::create(s, "scenario.json", "/clock");
    EXPECT_TRUE(r.ok()) << r.diagnostics.format();
    return r.ok() ? *r : ScenarioClock{};
}

struct BadSettings {
    const char* name;
    ClockSettings settings;
    const char* code;
    const char* where;
    const char* message;
};

class ClockBadSettings : public ::testing::TestWithParam<BadSettings> {};

TEST_P(ClockBadSettings, ReportsCodeWhereAndMessage) {
    const auto& p = GetParam();
    auto r = ScenarioClock::create(p.settings, "flood.json", "/clock");
    ASSERT_FALSE(r.ok()) << p.name;
    const Diagnostic* e = r.diagnostics.firstError();
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->code, p.code);
    EXPECT_EQ(e->file, "flood.json");
    EXPECT_EQ(e->where, p.where);
    EXPECT_NE(e->message.find(p.message), std::string::npos) << e->message;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

INSTANTIATE_TEST_SUITE_P(
    Table, ClockBadSettings,
    ::testing::Values(BadSettings{"nan start",
                                  {kNaN, 10, 1, RangeMode::Loop, true, {}, false},
                                  "ANIM_CLOCK_NOT_FINITE",
                                  "/clock/start",
                                  "clock start must be a finite"},
                      BadSettings{"inf end",
                                  {0, kInf, 1, RangeMode::Loop, true, {}, false},
                                  "ANIM_CLOCK_NOT_FINITE",
                                  "/clock/end",
                                  "clock end must be a finite"},
                      BadSettings{"nan rate",
                                  {0, 10, kNaN, RangeMode::Loop, true, {}, false},
                                  "ANIM_CLOCK_NOT_FINITE",
                                  "/clock/rate",
                                  "clock rate"},
                      BadSettings{"nan initial",
                                  {0, 10, 1, RangeMode::Loop, true, kNaN, false},
                                  "ANIM_CLOCK_NOT_FINITE",
                                  "/clock/initial",
                                  "clock initial"},
                      BadSettings{
                          "inverted",
                          {kT0 + 60, kT0, 1, RangeMode::Clamp, true, {}, false},
                          "ANIM_CLOCK_RANGE_INVERTED",
                          "/clock",
                          "clock end 2026-03-14T00:00:00Z is before start 2026-03-14T00:01:00Z"}),
    [](const auto& testInfo) {
        std::string n = testInfo.param.name;
        for (char& c : n)
            if (c == ' ') c = '_';
        return n;
    });

TEST(ScenarioClock, InitialTimeIsStartOrEndForNegativeRate) {
    EXPECT_EQ(makeClock(kT0, kT0 + 100, 10, RangeMode::Clamp).current(), kT0);
    EXPECT_EQ(makeClock(kT0, kT0 + 100, -10, RangeMode::Clamp).current(), kT0 + 100);
    EXPECT_EQ(makeClock(kT0, kT0 + 100, 1, RangeMode::Clamp, kT0 + 500).current(), kT0 + 100);
    EXPECT_EQ(makeClock(kT0, kT0 + 100, 1, RangeMode::Unbounded, kT0 + 500).current(), kT0 + 500);
}

TEST(ScenarioClock, LoopWrapsAtEnd) {
    auto c = makeClock(1000, 1100, 10, RangeMode::Loop);
    auto r = c.advance(5.0);
    EXPECT_DOUBLE_EQ(r.time, 1050);
    EXPECT_FALSE(r.wrapped);
    r = c.advance(6.0);  // 1110 -> 1010
    EXPECT_TRUE(r.wrapped);
    EXPECT_DOUBLE_EQ(c.current(), 1010);
    EXPECT_EQ(c.loops(), 1u);
    // Landing exactly on the end shows the start: positive-rate loops live in [start, end).
    c.seek(1090);
    c.advance(1.0);
    EXPECT_DOUBLE_EQ(c.current(), 1000);
    EXPECT_EQ(c.loops(), 2u);
}

TEST(ScenarioClock, LoopCountsSeveralWrapsInOneStalledFrame) {
    auto c = makeClock(0, 100, 10, RangeMode::Loop);
    c.advance(35.0);  // 350 -> 50 after three wraps
    EXPECT_DOUBLE_EQ(c.current(), 50);
    EXPECT_EQ(c.loops(), 3u);
}

TEST(ScenarioClock, NegativeRateLoopsBackwards) {
    auto c = makeClock(1000, 1100, -30, RangeMode::Loop);
    EXPECT_DOUBLE_EQ(c.current(), 1100);
    c.advance(1.0);
    EXPECT_DOUBLE_EQ(c.current(), 1070);
    auto r = c.advance(3.0);  // 980 -> 1080
    EXPECT_TRUE(r.wrapped);
    EXPECT_DOUBLE_EQ(c.current(), 1080);
    // Reaching start exactly wraps to end: negative-rate loops live in (start, end].
    c.seek(1030);
    c.advance(1.0);
    EXPECT_DOUBLE_EQ(c.current(), 1100);
}

TEST(ScenarioClock, ClampStopsAtEitherEnd) {
    auto c = makeClock(1000, 1100, 10, RangeMode::Clamp);
    auto r = c.advance(7.0);
    EXPECT_DOUBLE_EQ(r.time, 1070);
    EXPECT_FALSE(r.atEnd);
    r = c.advance(20.0);
    EXPECT_DOUBLE_EQ(r.time, 1100);
    EXPECT_TRUE(r.atEnd);
    EXPECT_FALSE(r.wrapped);
    c.setRate(-50);
    EXPECT_FALSE(c.advance(1.0).atEnd);
    r = c.advance(10.0);
    EXPECT_DOUBLE_EQ(r.time, 1000);
    EXPECT_TRUE(r.atEnd);
}

TEST(ScenarioClock, UnboundedRunsPastBothEnds) {
    auto c = makeClock(1000, 1100, 100, RangeMode::Unbounded);
    c.advance(3.0);
    EXPECT_DOUBLE_EQ(c.current(), 1300);
    c.setRate(-200);
    c.advance(2.0);
    EXPECT_DOUBLE_EQ(c.current(), 900);
    EXPECT_DOUBLE_EQ(c.elapsed(), -100);
}

TEST(ScenarioClock, PauseFreezesAndResumeContinues) {
    auto c = makeClock(0, 100, 2, RangeMode::Clamp);
    c.advance(1.0);
    c.pause();
    EXPECT_TRUE(c.paused());
    auto r = c.advance(10.0);
    EXPECT_DOUBLE_EQ(r.time, 2.0);
    EXPECT_FALSE(r.held);  // pausing is not waiting for data
    c.resume();
    c.advance(1.5);
    EXPECT_DOUBLE_EQ(c.current(), 5.0);
    c.togglePause();
    EXPECT_TRUE(c.paused());
}

TEST(ScenarioClock, WaitForDataHoldsTimeAndCountsHeldFrames) {
    auto c = makeClock(0, 100, 10, RangeMode::Clamp);
    c.advance(1.0);
    auto r = c.advance(1.0, /*nextStepReady=*/false);
    EXPECT_TRUE(r.held);
    EXPECT_DOUBLE_EQ(r.time, 10.0);
    c.advance(1.0, false);
    EXPECT_EQ(c.heldFrames(), 2u);
    EXPECT_EQ(c.heldInARow(), 2u);
    c.advance(1.0, true);
    EXPECT_DOUBLE_EQ(c.current(), 20.0);
    EXPECT_EQ(c.heldInARow(), 0u);
    EXPECT_EQ(c.heldFrames(), 2u);

    c.setWaitForData(false);  // play through: the screen holds (VisiblePair), time does not
    r = c.advance(1.0, false);
    EXPECT_FALSE(r.held);
    EXPECT_DOUBLE_EQ(c.current(), 30.0);
    EXPECT_EQ(c.heldFrames(), 2u);
}

TEST(ScenarioClock, WaitingGivesUpAfterMaxWaitSeconds) {
    ClockSettings s;
    s.start = 0;
    s.end = 1000;
    s.rate = 10;
    s.range = RangeMode::Clamp;
    s.maxWaitSeconds = 0.5;
    auto c = *ScenarioClock::create(s);
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(c.advance(0.1, false).held) << i;
    EXPECT_DOUBLE_EQ(c.current(), 0.0);
    auto r = c.advance(0.1, false);  // 0.6 s held: the valve opens
    EXPECT_FALSE(r.held);
    EXPECT_DOUBLE_EQ(r.time, 1.0);
    EXPECT_EQ(c.waitTimeouts(), 1u);
    EXPECT_EQ(c.heldFrames(), 5u);
    EXPECT_TRUE(c.advance(0.1, false).held);  // and the budget starts again
    c.setMaxWaitSeconds(0.0);                 // wait forever
    for (int i = 0; i < 100; ++i) c.advance(0.1, false);
    EXPECT_DOUBLE_EQ(c.current(), 1.0);
    EXPECT_EQ(c.waitTimeouts(), 1u);
}

TEST(ScenarioClock, PredictMatchesAdvanceWithoutChangingState) {
    auto c = makeClock(1000, 1100, 10, RangeMode::Loop, 1095.0);
    EXPECT_DOUBLE_EQ(c.predict(1.0), 1005.0);
    EXPECT_DOUBLE_EQ(c.current(), 1095.0);
    EXPECT_DOUBLE_EQ(c.advance(1.0).time, 1005.0);
    c.pause();
    EXPECT_DOUBLE_EQ(c.predict(1.0), 1005.0);
    auto clamp = makeClock(1000, 1100, 10, RangeMode::Clamp, 1095.0);
    EXPECT_DOUBLE_EQ(clamp.predict(3.0), 1100.0);
}

TEST(ScenarioClock, BadWallDeltasAreIgnored) {
    auto c = makeClock(0, 100, 10, RangeMode::Clamp);
    c.advance(std::numeric_limits<double>::quiet_NaN());
    c.advance(-1.0);
    c.advance(std::numeric_limits<double>::infinity());
    EXPECT_DOUBLE_EQ(c.current(), 0.0);
    c.setRate(std::numeric_limits<double>::infinity());
    EXPECT_DOUBLE_EQ(c.rate(), 10.0);
}

TEST(ScenarioClock, SeekAbsoluteOffsetAndRelative) {
    auto c = makeClock(kT0, kT0 + 3600, 60, RangeMode::Loop);
    EXPECT_EQ(c.seekSerial(), 0u);
    EXPECT_TRUE(c.seek(kT0 + 120));
    EXPECT_DOUBLE_EQ(c.current(), kT0 + 120);
    EXPECT_EQ(c.seekSerial(), 1u);
    EXPECT_TRUE(c.seek(TimeSpec{true, 1800}));
    EXPECT_DOUBLE_EQ(c.current(), kT0 + 1800);
    EXPECT_TRUE(c.seek(*parseTimeSpec("+1h30m")));  // outside: clamped, not wrapped
    EXPECT_DOUBLE_EQ(c.current(), kT0 + 3600);
    EXPECT_TRUE(c.seek(kT0 - 50));
    EXPECT_DOUBLE_EQ(c.current(), kT0);
    EXPECT_FALSE(c.seek(std::numeric_limits<double>::quiet_NaN()));
    EXPECT_DOUBLE_EQ(c.current(), kT0);
    EXPECT_EQ(c.seekSerial(), 4u);

    // Scrubbing wraps in Loop mode in the direction of the scrub.
    c.seekBy(-600);
    EXPECT_DOUBLE_EQ(c.current(), kT0 + 3000);
    c.seekBy(900);
    EXPECT_DOUBLE_EQ(c.current(), kT0 + 300);
    EXPECT_EQ(c.seekSerial(), 6u);

    auto clamp = makeClock(kT0, kT0 + 3600, 60, RangeMode::Clamp);
    clamp.seekBy(-600);
    EXPECT_DOUBLE_EQ(clamp.current(), kT0);
    auto free = makeClock(kT0, kT0 + 3600, 60, RangeMode::Unbounded);
    free.seek(kT0 + 7200);
    EXPECT_DOUBLE_EQ(free.current(), kT0 + 7200);
}

TEST(ScenarioClock, StepsBetweenIrregularKeys) {
    const std::vector<double> keys = {1000, 1010, 1035, 1100};
    auto c = makeClock(1000, 1100, 1, RangeMode::Clamp);
    EXPECT_TRUE(c.stepToNextKey(keys));
    EXPECT_DOUBLE_EQ(c.current(), 1010);
    EXPECT_TRUE(c.stepToNextKey(keys));
    EXPECT_DOUBLE_EQ(c.current(), 1035);
    EXPECT_TRUE(c.stepToPreviousKey(keys));
    EXPECT_DOUBLE_EQ(c.current(), 1010);
    // Between keys: previous is the key below, next the key above.
    c.seek(1020);
    EXPECT_TRUE(c.stepToPreviousKey(keys));
    EXPECT_DOUBLE_EQ(c.current(), 1010);
    // A hair past a key (rounding) still steps to the following key, not back onto it.
    c.seek(1010.0000002);
    EXPECT_TRUE(c.stepToNextKey(keys));
    EXPECT_DOUBLE_EQ(c.current(), 1035);
    c.seek(1100);
    const auto serial = c.seekSerial();
    EXPECT_FALSE(c.stepToNextKey(keys));  // Clamp: nothing after the last key
    EXPECT_EQ(c.seekSerial(), serial);
    c.seek(1000);
    EXPECT_FALSE(c.stepToPreviousKey(keys));
}

TEST(ScenarioClock, StepWrapsInLoopAndIgnoresKeysOutsideRange) {
    const std::vector<double> keys = {1100, 990, 1035, 1010, 1200};  // unsorted, two outside
    auto c = makeClock(1000, 1100, 1, RangeMode::Loop, 1050.0);
    EXPECT_TRUE(c.stepToNextKey(keys));
    EXPECT_DOUBLE_EQ(c.current(), 1100);
    EXPECT_TRUE(c.stepToNextKey(keys));  // wraps to the first key inside the range
    EXPECT_DOUBLE_EQ(c.current(), 1010);
    EXPECT_TRUE(c.stepToPreviousKey(keys));  // wraps to the last one
    EXPECT_DOUBLE_EQ(c.current(), 1100);
    EXPECT_FALSE(c.stepToNextKey(std::vector<double>{}));
}

TEST(ScenarioClock, ProgressForTheScrubBar) {
    auto c = makeClock(0, 200, 1, RangeMode::Clamp, 50.0);
    EXPECT_DOUBLE_EQ(c.progress(), 0.25);
    EXPECT_DOUBLE_EQ(makeClock(5, 5, 1, RangeMode::Loop).progress(), 0.0);
}

TEST(ScenarioClock, ZeroLengthLoopPinsTime) {
    auto c = makeClock(5, 5, 3, RangeMode::Loop);
    c.advance(10.0);
    EXPECT_DOUBLE_EQ(c.current(), 5.0);
}

TEST(RenderTimeline, FramesAreDeterministicAndEndOnT1) {
    // 1 h of data at 60x rendered at 30 fps: 60 s of video, 1801 frames.
    const double t1 = kT0 + 3600;
    EXPECT_EQ(frameCount(kT0, t1, 30, 60), 1801);
    EXPECT_EQ(timeForFrame(kT0, t1, 30, 0, 60), kT0);
    EXPECT_EQ(timeForFrame(kT0, t1, 30, 1, 60), kT0 + 2.0);
    EXPECT_EQ(timeForFrame(kT0, t1, 30, 900, 60), kT0 + 1800.0);
    EXPECT_EQ(timeForFrame(kT0, t1, 30, 1800, 60), t1);
    EXPECT_EQ(timeForFrame(kT0, t1, 30, 5000, 60), t1);  // clamped
    // Multiplication, not accumulation: frame k equals t0 + k * step exactly (fractional step).
    const double step = 1.0 / 3.0;
    for (std::int64_t k : {1, 7, 100, 9999})
        EXPECT_EQ(timeForFrame(0, 1e6, 3, k), static_cast<double>(k) * step) << k;
    // Not a whole number of steps: the last frame is the last step before t1.
    EXPECT_EQ(frameCount(0, 10, 4, 3), 14);  // step 0.75 -> 0 .. 9.75
    EXPECT_DOUBLE_EQ(timeForFrame(0, 10, 4, 13, 3), 9.75);
}

TEST(RenderTimeline, BackwardsAndBadInputs) {
    EXPECT_EQ(frameCount(100, 40, 2, 10), 13);
    EXPECT_DOUBLE_EQ(timeForFrame(100, 40, 2, 3, 10), 85);
    EXPECT_DOUBLE_EQ(timeForFrame(100, 40, 2, 12, -10), 40);  // sign of rate is irrelevant
    EXPECT_EQ(timeForFrame(100, 200, 0, 5), 100);
    EXPECT_EQ(timeForFrame(100, 200, 30, 5, 0), 100);
    EXPECT_EQ(timeForFrame(100, 200, 30, -5), 100);
    EXPECT_EQ(timeForFrame(100, std::numeric_limits<double>::quiet_NaN(), 30, 5), 100);
    EXPECT_EQ(frameCount(100, 200, -1), 1);
    EXPECT_EQ(frameCount(100, 100, 30), 1);
}

TEST(ScenarioClock, RangeModeNames) {
    EXPECT_EQ(parseRangeMode("loop"), RangeMode::Loop);
    EXPECT_EQ(parseRangeMode("clamp"), RangeMode::Clamp);
    EXPECT_EQ(parseRangeMode("unbounded"), RangeMode::Unbounded);
    EXPECT_FALSE(parseRangeMode("Loop").has_value());
    EXPECT_STREQ(toString(RangeMode::Unbounded), "unbounded");
}

}  // namespace
}  // namespace kiosk::anim
