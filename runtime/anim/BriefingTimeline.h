#pragma once

#include <cstdint>
#include <vector>

namespace kiosk::anim {

/**
 * @brief One chapter of a briefing in numbers: the data-time span it plays (from == to for a
 * single time), how many playback seconds that takes, and whether playback pauses at its end.
 */
struct ChapterSpan {
    double from = 0;
    double to = 0;
    double seconds = 5;  ///< playback seconds, > 0
    bool pause = false;
};

/** @brief Data time `elapsed` playback seconds into a chapter (clamped to its end). */
double chapterTimeAt(const ChapterSpan& chapter, double elapsed) noexcept;

/** @brief One frame of an exported briefing. */
struct BriefingFrame {
    double time = 0;  ///< data time
    int chapter = 0;
};

/** @brief Where a chapter lies in an exported briefing (frame indices, end exclusive). */
struct ChapterFrames {
    std::int64_t first = 0;
    std::int64_t end = 0;
};

/**
 * @brief The frames of a briefing exported back to back at `fps`: each chapter gets
 * max(1, round(seconds * fps)) frames from `from` to `to` (both ends shown), then, when it
 * pauses, `holdSeconds` of its last frame (a video cannot wait for a key press).
 * `spans`, when given, receives each chapter's frame range (for the chapter markers).
 */
std::vector<BriefingFrame> briefingFrames(const std::vector<ChapterSpan>& chapters, double fps,
                                          double holdSeconds,
                                          std::vector<ChapterFrames>* spans = nullptr);

}  // namespace kiosk::anim
