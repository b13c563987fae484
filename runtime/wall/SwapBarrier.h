#pragma once

#include "runtime/wall/SyncMessages.h"

#include <cstdint>
#include <vector>

// The leader's side of the swap barrier as a pure state machine: time comes in as arguments,
// messages as values; ZmqTransport and WallNode move them. Unit-tested without sockets.
namespace kiosk::wall {

/**
 * @brief Per frame: begin(), the leader's own leaderReady(), followers' onReady(); release
 * when releasable(). A follower that is not ready by the deadline is dropped (not waited for
 * again); any report from a dropped follower (even for an old frame: it is alive and
 * listening) makes it a member again from the next frame, so it rejoins at the current state.
 *
 * Wall-wide atomic steps: stepResident() is true when the leader and every follower that made
 * this frame's barrier had the sequence pair at this frame's data time resident; the leader
 * then lets the next frame's stepTime move to that time, so a new step appears on every screen
 * in the same swap. Dropped followers do not hold the wall back.
 */
class SwapBarrier {
public:
    SwapBarrier(std::vector<std::uint32_t> followerScreens, double deadlineSeconds);

    /** @brief Start frame `frame` at `now`; it waits at most `waitSeconds` (the deadline). */
    void begin(std::uint64_t frame, double now, double waitSeconds);
    void begin(std::uint64_t frame, double now) { begin(frame, now, mDeadlineSeconds); }
    /** @brief The leader drew its own frame (`resident`: with every tile it needs). */
    void leaderReady(bool stepResident);
    /** @brief A follower's report. Unknown screens and other frames only count as signs of life. */
    void onReady(const Ready& r);
    /** @brief The leader is ready and so is every member, or the deadline has passed. */
    bool releasable(double now) const;
    double deadline() const noexcept { return mDeadline; }
    /** @brief Close the frame: drop members that were not ready; the message to publish. */
    Release release();

    bool stepResident() const noexcept { return mStepResident; }
    std::uint64_t frame() const noexcept { return mFrame; }
    std::size_t members() const;
    bool isMember(std::uint32_t screen) const;
    /** @brief Screens dropped at the last release (for the log). */
    const std::vector<std::uint32_t>& lastDropped() const noexcept { return mDropped; }

private:
    struct Follower {
        std::uint32_t screen = 0;
        bool member = true;   ///< waited for this frame
        bool rejoin = false;  ///< report seen while dropped: member from the next frame
        bool ready = false;
        bool stepResident = false;
    };
    Follower* find(std::uint32_t screen);

    std::vector<Follower> mFollowers;
    double mDeadlineSeconds;
    double mDeadline = 0;
    std::uint64_t mFrame = 0;
    bool mOpen = false;
    bool mLeaderReady = false;
    bool mLeaderStep = false;
    bool mStepResident = false;
    std::vector<std::uint32_t> mDropped;
};

}  // namespace kiosk::wall
