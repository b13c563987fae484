#pragma once

#include "runtime/wall/SyncMessages.h"

#include <cstdint>
#include <optional>

// The follower's side of the sync protocol as a pure state machine (no sockets, no clock of its
// own): messages in, decisions out. WallNode drives it from the ZeroMQ transport.
namespace kiosk::wall {

/**
 * @brief Draw exactly the leader's state, report ready once drawn with every tile resident,
 * swap when released.
 *
 * Messages are fed in arrival order. The newest state wins: a follower that fell behind (slow,
 * dropped, restarted) skips the states it missed and draws the current one, which is how it
 * rejoins. A release for the frame on screen-to-be swaps it (also a late one); a release for a
 * frame it never drew is ignored. If no state arrives for `silentSeconds` the leader is
 * considered gone: the last frame stays on screen (nothing to draw, nothing to swap).
 */
class FollowerSync {
public:
    FollowerSync(std::uint32_t screen, double silentSeconds)
        : mScreen(screen), mSilent(silentSeconds) {}

    void onState(const FrameState& s, double now);
    void onRelease(const Release& r);
    void onStop() { mStopped = true; }

    /** @brief The newest state not yet drawn (taking it makes it the frame being drawn). */
    std::optional<FrameState> takeStateToDraw();
    /** @brief The frame being drawn / drawn and not yet swapped. */
    std::optional<std::uint64_t> pendingFrame() const { return mPending; }
    /**
     * @brief The pending frame was drawn; `resident`: every tile it needs is resident. Returns
     * the report to push the first time it is resident (at most once per frame).
     */
    std::optional<Ready> drawn(bool resident, bool stepResident, std::uint64_t scenarioHash);
    /** @brief A state newer than the pending frame arrived (the leader moved on without us). */
    bool hasNewerState() const { return mNewest && (!mPending || mNewest->frame > *mPending); }
    /** @brief The pending frame has been released: swap it now. */
    bool swapDue() const;
    /** @brief The swap happened; returns the frame now on screen. */
    std::uint64_t swapped();

    bool leaderSilent(double now) const { return mHaveState && now - mLastState > mSilent; }
    bool stopped() const noexcept { return mStopped; }
    std::optional<std::uint64_t> shownFrame() const { return mShown; }

private:
    std::uint32_t mScreen;
    double mSilent;
    std::optional<FrameState> mNewest;  ///< received, not yet taken
    std::optional<std::uint64_t> mPending;
    std::optional<std::uint64_t> mShown;
    std::optional<std::uint64_t> mReleased;  ///< newest release seen
    bool mReadySent = false;
    bool mHaveState = false;
    double mLastState = 0;
    bool mStopped = false;
};

}  // namespace kiosk::wall
