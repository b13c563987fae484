#pragma once

#include <array>
#include <cstdint>

namespace kiosk::anim {

/**
 * @brief Limits and pace of the frame-rate governor (docs/animation.md "Frame-rate governor").
 * `targetFps` 0 turns it off.
 */
struct GovernorSettings {
    double targetFps = 0.0;  ///< the kiosk's frame rate to hold (frames per second)
    double maxTauFactor =
        4.0;               ///< tauGeom/tauTex are raised to at most this many times the scenario's
    double maxTau = 64.0;  ///< and never beyond this many pixels (the scenario format's limit)
    double minRenderScale = 0.5;  ///< the render target shrinks to at least this fraction per axis
    double smoothing = 0.3;       ///< weight of the newest frame in the moving average
    int settleFrames = 4;         ///< frames ignored after a change (new tiles, new target size)
    int overFrames = 3;           ///< consecutive over-budget frames before a step up
    int underFrames = 30;         ///< consecutive frames with headroom before a step down
    double headroom = 0.7;        ///< "headroom" = average below this fraction of the budget
};

/** @brief What the renderer should use for the next frame. */
struct GovernorState {
    double tauGeom = 1.0;
    double tauTex = 1.0;
    double renderScale = 1.0;  ///< fraction of the output size rendered (upscaled after)
    int level = 0;             ///< rung of the ladder: 0 = the scenario's own settings
    double averageMs = 0.0;    ///< moving average of the measured frame time
    bool active = false;       ///< a target frame rate is set
};

/**
 * @brief Holds a target frame rate by trading fidelity for time (pure logic, no GL: the caller
 * measures frames and applies the state). Over budget, it climbs a ladder: first tauGeom and
 * tauTex together (x1.5, x2, x3, x4 of the scenario's, within the settings' limits), then the
 * render scale (0.85, 0.7, 0.6, 0.5 of the output size). With headroom it steps back down one
 * rung at a time. Hysteresis: a step up needs `overFrames` slow frames in a row, a step down
 * `underFrames` frames below `headroom` of the budget, every change is followed by
 * `settleFrames` unjudged frames, and a step down that had to be undone within twice its wait
 * doubles the wait for that rung (up to 32x), so a cost that sits between two rungs does not
 * make it oscillate.
 */
class FrameGovernor {
public:
    static constexpr int kRungs = 9;

    FrameGovernor(const GovernorSettings& settings, double tauGeom, double tauTex);

    /** @brief Feed the time the last frame took (ms); returns the state for the next frame. */
    const GovernorState& frameDone(double frameMs);
    const GovernorState& state() const noexcept { return mState; }
    /** @brief Frame budget in ms (1000 / targetFps); 0 when off. */
    double budgetMs() const noexcept { return mBudgetMs; }

private:
    GovernorState rung(int level) const;
    int nextRung(int from, int dir) const;
    void apply(int level);

    GovernorSettings mSettings;
    double mBaseGeom, mBaseTex, mBudgetMs = 0.0;
    GovernorState mState;
    int mSettle = 0, mOver = 0, mUnder = 0;
    std::int64_t mFrame = 0, mSteppedDownAt = -1;
    int mSteppedDownFrom = -1;
    std::array<int, kRungs> mUnderNeeded{};
};

}  // namespace kiosk::anim
