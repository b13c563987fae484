#include "runtime/anim/BriefingPlayer.h"
#include "runtime/anim/BriefingTimeline.h"

#include <gtest/gtest.h>

namespace kiosk::anim {
namespace {

// Chapter 0: 0..3600 over 3 s; chapter 1: a single time (7200) for 2 s, pausing at its end.
const std::vector<ChapterSpan> kChapters = {{0, 3600, 3, false}, {7200, 7200, 2, true}};

TEST(BriefingTimeline, ChaptersBackToBackWithBothEndsAndAHoldAtAPause) {
    std::vector<ChapterFrames> spans;
    const auto frames = briefingFrames(kChapters, 2.0, 1.5, &spans);
    // 6 frames for chapter 0, 4 for chapter 1, then 3 (1.5 s at 2 fps) holding its end.
    ASSERT_EQ(frames.size(), 13u);
    ASSERT_EQ(spans.size(), 2u);
    EXPECT_EQ(spans[0].first, 0);
    EXPECT_EQ(spans[0].end, 6);
    EXPECT_EQ(spans[1].first, 6);
    EXPECT_EQ(spans[1].end, 13);
    EXPECT_DOUBLE_EQ(frames[0].time, 0);
    EXPECT_DOUBLE_EQ(frames[1].time, 720);
    EXPECT_DOUBLE_EQ(frames[5].time, 3600);
    EXPECT_EQ(frames[5].chapter, 0);
    for (std::size_t i = 6; i < frames.size(); ++i) {
        EXPECT_DOUBLE_EQ(frames[i].time, 7200);
        EXPECT_EQ(frames[i].chapter, 1);
    }
    EXPECT_TRUE(briefingFrames(kChapters, 0.0, 1.0).empty());
}

TEST(BriefingTimeline, TimeWithinAChapterIsClamped) {
    EXPECT_DOUBLE_EQ(chapterTimeAt(kChapters[0], 1.5), 1800);
    EXPECT_DOUBLE_EQ(chapterTimeAt(kChapters[0], 99), 3600);
    EXPECT_DOUBLE_EQ(chapterTimeAt(kChapters[0], -1), 0);
}

TEST(BriefingPlayer, PlaysOnPausesAndSteps) {
    BriefingPlayer p(kChapters);
    EXPECT_DOUBLE_EQ(p.advance(1.5), 1800);
    EXPECT_DOUBLE_EQ(p.advance(1.0, false), 1800);  // waiting for data holds
    p.advance(1.6);                                 // past chapter 0's end: on to chapter 1
    EXPECT_EQ(p.chapter(), 1);
    p.advance(5.0);
    EXPECT_TRUE(p.atPause());  // chapter 1 pauses at its end and stays there
    p.advance(100.0);
    EXPECT_EQ(p.chapter(), 1);
    EXPECT_DOUBLE_EQ(p.time(), 7200);
    p.togglePause();  // at a pause, "play" goes on: after the last chapter, the first
    EXPECT_EQ(p.chapter(), 0);
    EXPECT_FALSE(p.atPause());
    p.togglePause();  // mid-chapter it pauses playback
    EXPECT_TRUE(p.userPaused());
    EXPECT_DOUBLE_EQ(p.advance(1.0), 0);
    p.togglePause();
    p.next();
    EXPECT_EQ(p.chapter(), 1);
    p.previous();
    EXPECT_EQ(p.chapter(), 0);
    p.previous();  // stays on the first
    EXPECT_EQ(p.chapter(), 0);
}

}  // namespace
}  // namespace kiosk::anim
