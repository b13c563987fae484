#include "runtime/anim/VisiblePair.h"

namespace kiosk::anim {

DisplayPair VisiblePair::commit(const FrameBracket& wanted, bool wantedComplete,
                                std::span<const double> frameTimes, double t) noexcept {
    if (wantedComplete) {
        if (!mShown.hasPair || mShown.i0 != wanted.i0 || mShown.i1 != wanted.i1) ++mSwitches;
        mShown.hasPair = true;
        mShown.i0 = wanted.i0;
        mShown.i1 = wanted.i1;
        mShown.alpha = wanted.alpha;
        mShown.holding = false;
        mShown.heldFrames = 0;
        return mShown;
    }
    mShown.holding = true;
    ++mShown.heldFrames;
    ++mTotalHeld;
    // A held pair tracks the clock within its own interval only: never beyond its frames.
    if (mShown.hasPair) {
        if (mShown.i0 < frameTimes.size() && mShown.i1 < frameTimes.size())
            mShown.alpha = alphaWithin(frameTimes, mShown.i0, mShown.i1, t);
        else
            mShown = DisplayPair{false, 0, 0, 0.0, true, mShown.heldFrames};  // sequence shrank
    }
    return mShown;
}

}  // namespace kiosk::anim
