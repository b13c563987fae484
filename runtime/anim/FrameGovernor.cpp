#include "runtime/anim/FrameGovernor.h"

#include <algorithm>

namespace kiosk::anim {
namespace {

// The ladder: tau factor and render scale per rung. Raising tau first keeps full-resolution
// pixels (fewer triangles and texels, same sharpness of edges); scaling the target down then
// cuts the fill cost, which is what remains on a software rasteriser.
constexpr double kTauFactor[FrameGovernor::kRungs] = {1.0, 1.5, 2.0, 3.0, 4.0, 4.0, 4.0, 4.0, 4.0};
constexpr double kScale[FrameGovernor::kRungs] = {1.0, 1.0, 1.0, 1.0, 1.0, 0.85, 0.7, 0.6, 0.5};
constexpr int kMaxBackoff = 32;

}  // namespace

FrameGovernor::FrameGovernor(const GovernorSettings& settings, double tauGeom, double tauTex)
    : mSettings(settings), mBaseGeom(tauGeom), mBaseTex(tauTex) {
    mState.active = settings.targetFps > 0.0;
    mBudgetMs = mState.active ? 1000.0 / settings.targetFps : 0.0;
    mUnderNeeded.fill(std::max(1, settings.underFrames));
    apply(0);
}

GovernorState FrameGovernor::rung(int level) const {
    GovernorState r = mState;
    r.level = level;
    const double f = std::min(kTauFactor[level], std::max(1.0, mSettings.maxTauFactor));
    r.tauGeom = std::max(mBaseGeom, std::min(mBaseGeom * f, mSettings.maxTau));
    r.tauTex = std::max(mBaseTex, std::min(mBaseTex * f, mSettings.maxTau));
    r.renderScale = std::max(kScale[level], std::min(1.0, mSettings.minRenderScale));
    return r;
}

int FrameGovernor::nextRung(int from, int dir) const {
    // A rung that changes nothing (its limits are reached) cannot buy time: skip it.
    const GovernorState here = rung(from);
    for (int l = from + dir; l >= 0 && l < kRungs; l += dir) {
        const GovernorState r = rung(l);
        if (r.tauGeom != here.tauGeom || r.tauTex != here.tauTex ||
            r.renderScale != here.renderScale)
            return l;
    }
    return -1;
}

void FrameGovernor::apply(int level) {
    const double average = mState.averageMs;
    mState = rung(level);
    mState.averageMs = average;
    mSettle = mSettings.settleFrames;
    mOver = mUnder = 0;
}

const GovernorState& FrameGovernor::frameDone(double frameMs) {
    ++mFrame;
    if (!mState.active || !(frameMs >= 0.0)) return mState;
    const double a = std::clamp(mSettings.smoothing, 0.01, 1.0);
    mState.averageMs =
        mState.averageMs > 0.0 ? (1.0 - a) * mState.averageMs + a * frameMs : frameMs;
    if (mSettle > 0) {
        // The frames right after a change still carry the old cost (tiles of the old tau in
        // flight, the first frame at a new size): restart the average from what comes next.
        --mSettle;
        mState.averageMs = frameMs;
        return mState;
    }
    const int level = mState.level;
    if (mState.averageMs > mBudgetMs) {
        mUnder = 0;
        if (++mOver >= std::max(1, mSettings.overFrames)) {
            const int up = nextRung(level, +1);
            if (up < 0) {
                mOver = 0;
                return mState;
            }
            // Back up to the rung just left: the step down came too early, so leaving that
            // rung downwards waits twice as long from now on.
            auto& wait = mUnderNeeded[std::size_t(up)];
            if (mSteppedDownFrom == up && mFrame - mSteppedDownAt <= 2 * wait)
                wait = std::min(wait * 2, kMaxBackoff * std::max(1, mSettings.underFrames));
            mSteppedDownFrom = -1;
            apply(up);
        }
    } else if (mState.averageMs < mSettings.headroom * mBudgetMs) {
        mOver = 0;
        if (level > 0 && ++mUnder >= mUnderNeeded[std::size_t(level)]) {
            const int down = nextRung(level, -1);
            if (down >= 0) {
                mSteppedDownFrom = level;
                mSteppedDownAt = mFrame;
                apply(down);
            } else {
                mUnder = 0;
            }
        }
    } else {
        mOver = mUnder = 0;
    }
    return mState;
}

}  // namespace kiosk::anim
