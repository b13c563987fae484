#include "runtime/wall/FollowerSync.h"

namespace kiosk::wall {

void FollowerSync::onState(const FrameState& s, double now) {
    mHaveState = true;
    mLastState = now;
    // The leader republishes a state while it waits for nodes to join: nothing new to draw.
    if ((mPending && s.frame <= *mPending) || (mShown && s.frame <= *mShown)) return;
    if (!mNewest || s.frame > mNewest->frame) mNewest = s;
}

void FollowerSync::onRelease(const Release& r) {
    if (!mReleased || r.frame > *mReleased) mReleased = r.frame;
}

std::optional<FrameState> FollowerSync::takeStateToDraw() {
    if (!mNewest) return std::nullopt;
    FrameState s = std::move(*mNewest);
    mNewest.reset();
    mPending = s.frame;
    mReadySent = false;
    return s;
}

std::optional<Ready> FollowerSync::drawn(bool resident, bool stepResident,
                                         std::uint64_t scenarioHash) {
    if (!mPending || mReadySent || !resident) return std::nullopt;
    mReadySent = true;
    Ready r;
    r.screen = mScreen;
    r.frame = *mPending;
    r.resident = resident;
    r.stepResident = stepResident;
    r.scenarioHash = scenarioHash;
    return r;
}

bool FollowerSync::swapDue() const {
    return mPending && mReleased && *mReleased >= *mPending;
}

std::uint64_t FollowerSync::swapped() {
    mShown = mPending;
    mPending.reset();
    return *mShown;
}

}  // namespace kiosk::wall
