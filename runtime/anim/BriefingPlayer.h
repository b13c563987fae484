#pragma once

#include "runtime/anim/BriefingTimeline.h"

#include <vector>

namespace kiosk::anim {

/**
 * @brief Live briefing playback (`play`): chapters in order, each from its `from` to its `to`
 * over its playback seconds; at a chapter's end either on to the next one or, when the chapter
 * pauses, holding there until next() / togglePause(). After the last chapter it starts over
 * (a kiosk loops). Render thread only; advanced once per frame.
 */
class BriefingPlayer {
public:
    explicit BriefingPlayer(std::vector<ChapterSpan> chapters);

    /** @brief Advance `dt` wall seconds (held while `ready` is false); returns the data time. */
    double advance(double dt, bool ready = true);
    void next();
    void previous();
    /** @brief At a chapter's pause: go on to the next; otherwise pause / resume playback. */
    void togglePause();
    void goTo(int chapter);

    int chapter() const noexcept { return mChapter; }
    double time() const noexcept;
    /** @brief Data time `seconds` of playback ahead in this chapter (prefetch); now if holding. */
    double timeAhead(double seconds) const noexcept;
    bool atPause() const noexcept { return mAtPause; }
    bool userPaused() const noexcept { return mUserPaused; }
    int chapterCount() const noexcept { return int(mChapters.size()); }

private:
    std::vector<ChapterSpan> mChapters;
    int mChapter = 0;
    double mElapsed = 0;
    bool mAtPause = false;
    bool mUserPaused = false;
};

}  // namespace kiosk::anim
