#pragma once

#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Session.h"
#include "runtime/app/WallScreen.h"
#include "runtime/core/Result.h"
#include "runtime/wall/FollowerSync.h"
#include "runtime/wall/SwapBarrier.h"
#include "runtime/wall/ZmqTransport.h"

#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>

// `play --wall`: one node's part in the wall's sync (docs/wall.md "Sync protocol"). PlayCommand
// calls beginFrame() before drawing, barrier() after drawing and swapped() after the swap; the
// protocol decisions are SwapBarrier's (leader) and FollowerSync's (followers).
namespace kiosk::app {

class WallNode {
public:
    /** @brief Bind (leader) or connect (follower) the sync sockets; `logPath`: per-swap JSON lines.
     */
    static Result<std::unique_ptr<WallNode>> create(WallScreen screen, const std::string& logPath);
    ~WallNode();

    const WallScreen& screen() const noexcept { return mScreen; }
    bool isLeader() const noexcept { return mScreen.isLeader(); }

    /**
     * @brief Leader: publish the frame's state from its playback (clock or briefing chapter),
     * camera and briefing chapter. Follower: wait (at most
     * `maxWaitSeconds`) for the leader's next state. False when there is nothing to draw (no
     * state yet, the leader is silent: the last frame stays on screen) or a stop arrived.
     */
    bool beginFrame(Session& session, double dataTime, const math::Viewpoint& viewpoint,
                    const scene::Playback& playback, double maxWaitSeconds);
    /** @brief The frame to draw (valid after beginFrame() returned true). */
    double dataTime() const { return mState.dataTime; }
    double stepTime() const { return mState.stepTime; }
    const math::Viewpoint& viewpoint() const { return mState.camera; }
    int chapter() const { return mState.chapter; }
    scene::Playback playback() const;

    /**
     * @brief After the first draw: redraw (`redraw`) until every tile the frame needs is
     * resident, report ready, and wait for the swap release (leader: collect reports, release
     * when all are ready or at the deadline). True: swap now; false: keep the last frame.
     */
    bool barrier(Session& session, const std::function<void()>& redraw);
    /** @brief Record the swap (log line). */
    void swapped(const scene::SceneFrameInfo& info);
    /** @brief Leader: the last frame's step was resident on every node (the clock may go on). */
    bool stepResident() const { return mStepResident; }
    /** @brief Follower: the leader said stop. */
    bool stopped() const { return mFollower && mFollower->stopped(); }
    /** @brief Leader: tell followers to stop (clean exit). */
    void stop();

private:
    explicit WallNode(WallScreen screen) : mScreen(std::move(screen)) {}
    bool leaderBarrier(Session& session, const std::function<void()>& redraw);
    bool followerBarrier(Session& session, const std::function<void()>& redraw);
    void handle(const wall::Bytes& message, double now);
    /** @brief Follower: handle every message already queued. */
    void drain();
    std::uint64_t hashOf(const Session& session);

    WallScreen mScreen;
    std::unique_ptr<wall::LeaderTransport> mLeaderT;
    std::unique_ptr<wall::FollowerTransport> mFollowerT;
    std::unique_ptr<wall::SwapBarrier> mBarrier;
    std::unique_ptr<wall::FollowerSync> mFollower;
    wall::FrameState mState;
    wall::Release mLastRelease;
    std::uint64_t mFrame = 0;
    double mStepTime = 0;
    bool mHaveStep = false;
    bool mStepResident = true;
    const Session* mHashedSession = nullptr;
    std::uint64_t mHash = 0;
    std::uint64_t mWarnedHash = 0;
    bool mWarnedSilent = false;
    bool mReadySent = false;
    double mWaitUs = 0;  ///< leader: last frame's wait from its own ready to the release  ///<
                         ///< follower: the pending frame was reported
    std::FILE* mLog = nullptr;
};

}  // namespace kiosk::app
