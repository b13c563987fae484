#include "runtime/anim/BriefingPlayer.h"

#include <algorithm>
#include <cmath>

namespace kiosk::anim {

BriefingPlayer::BriefingPlayer(std::vector<ChapterSpan> chapters)
    : mChapters(std::move(chapters)) {}

double BriefingPlayer::time() const noexcept {
    return mChapters.empty() ? 0.0 : chapterTimeAt(mChapters[std::size_t(mChapter)], mElapsed);
}

double BriefingPlayer::timeAhead(double seconds) const noexcept {
    if (mChapters.empty() || mAtPause || mUserPaused) return time();
    return chapterTimeAt(mChapters[std::size_t(mChapter)], mElapsed + seconds);
}

double BriefingPlayer::advance(double dt, bool ready) {
    if (mChapters.empty()) return 0.0;
    if (mAtPause || mUserPaused || !ready || !(dt > 0) || !std::isfinite(dt)) return time();
    mElapsed += dt;
    const ChapterSpan& c = mChapters[std::size_t(mChapter)];
    if (mElapsed >= c.seconds) {
        if (c.pause) {
            mElapsed = c.seconds;
            mAtPause = true;
        } else {
            next();
        }
    }
    return time();
}

void BriefingPlayer::goTo(int chapter) {
    if (mChapters.empty()) return;
    const int n = int(mChapters.size());
    mChapter = ((chapter % n) + n) % n;
    mElapsed = 0;
    mAtPause = false;
}

void BriefingPlayer::next() {
    goTo(mChapter + 1);
}

void BriefingPlayer::previous() {
    // Like a player's "previous": well into a chapter it restarts it, near its start it goes back.
    if (mElapsed > 2.0 && !mAtPause)
        goTo(mChapter);
    else
        goTo(std::max(0, mChapter - 1));
}

void BriefingPlayer::togglePause() {
    if (mAtPause)
        next();
    else
        mUserPaused = !mUserPaused;
}

}  // namespace kiosk::anim
