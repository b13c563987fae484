#include "runtime/app/WallNode.h"

#include "runtime/core/Log.h"

#include <chrono>
#include <fstream>
#include <iterator>

namespace kiosk::app {
namespace {

constexpr const char* kTag = "wall";
/** The first frame waits this long for every follower to join (they start at different times). */
constexpr double kJoinSeconds = 10.0;
/** While waiting for joiners, the first state is republished this often (PUB drops messages
 * sent before a subscriber connected). */
constexpr double kRepublishSeconds = 0.05;
/** A follower that hears nothing for this long keeps its last frame and says so. */
constexpr double kLeaderSilentSeconds = 2.0;

double monotonicSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

Result<std::unique_ptr<WallNode>> WallNode::create(WallScreen screen, const std::string& logPath) {
    std::unique_ptr<WallNode> n(new WallNode(std::move(screen)));
    const auto& w = n->mScreen.wall;
    if (n->isLeader()) {
        auto t = wall::LeaderTransport::bind(w.sync);
        if (!t) return t.diagnostics;
        n->mLeaderT = std::move(*t.value);
        std::vector<std::uint32_t> followers;
        for (std::size_t i = 0; i < w.screens.size(); ++i)
            if (int(i) != n->mScreen.screen) followers.push_back(std::uint32_t(i));
        n->mBarrier = std::make_unique<wall::SwapBarrier>(followers, w.sync.deadlineMs / 1000.0);
    } else {
        auto t = wall::FollowerTransport::connect(w.sync);
        if (!t) return t.diagnostics;
        n->mFollowerT = std::move(*t.value);
        n->mFollower = std::make_unique<wall::FollowerSync>(std::uint32_t(n->mScreen.screen),
                                                            kLeaderSilentSeconds);
    }
    if (!logPath.empty()) {
        n->mLog = std::fopen(logPath.c_str(), "w");
        if (!n->mLog) {
            Diagnostics d;
            d.error("WALL_LOG", logPath, "", "cannot write the wall log");
            return d;
        }
    }
    KIOSK_LOG_INFO(kTag, "screen %s (%s) of %s", n->mScreen.self().id.c_str(),
                   n->isLeader() ? "leader" : "follower", w.file.c_str());
    return n;
}

WallNode::~WallNode() {
    if (mLog) std::fclose(mLog);
}

std::uint64_t WallNode::hashOf(const Session& session) {
    if (mHashedSession == &session) return mHash;
    // FNV-1a over the scenario's files: nodes must draw the same scenario, byte for byte.
    std::uint64_t h = 1469598103934665603ull;
    for (const auto& f : session.scenario().sourceFiles) {
        std::ifstream in(f, std::ios::binary);
        for (std::istreambuf_iterator<char> it(in), end; it != end; ++it)
            h = (h ^ std::uint8_t(*it)) * 1099511628211ull;
    }
    mHashedSession = &session;
    mHash = h;
    return h;
}

scene::Playback WallNode::playback() const {
    scene::Playback p;
    p.rate = mState.rate;
    p.range = anim::RangeMode(mState.rangeMode);
    p.start = mState.rangeStart;
    p.end = mState.rangeEnd;
    p.seekSerial = mState.seekSerial;
    p.paused = mState.paused;
    return p;
}

void WallNode::handle(const wall::Bytes& m, double now) {
    switch (wall::messageType(m).value_or(wall::MessageType::Ready)) {
        case wall::MessageType::State:
            if (auto s = wall::decodeState(m)) mFollower->onState(*s, now);
            break;
        case wall::MessageType::Release:
            if (auto r = wall::decodeRelease(m)) mFollower->onRelease(*r);
            break;
        case wall::MessageType::Stop:
            mFollower->onStop();
            break;
        default:
            break;
    }
}

void WallNode::drain() {
    while (auto m = mFollowerT->receive(std::chrono::microseconds(0)))
        handle(*m, monotonicSeconds());
}

bool WallNode::beginFrame(Session& session, double dataTime, const math::Viewpoint& vp,
                          const scene::Playback& p, double maxWait) {
    if (isLeader()) {
        if (!mHaveStep) mStepTime = dataTime, mHaveStep = true;
        mState = {};
        mState.frame = ++mFrame;
        mState.dataTime = dataTime;
        mState.stepTime = mStepTime;
        mState.camera = vp;
        mState.scenarioHash = hashOf(session);
        mState.scenarioId = session.scenario().sourceFiles.empty()
                                ? std::string()
                                : session.scenario().sourceFiles.front().filename().string();
        mState.rate = p.rate;
        mState.rangeStart = p.start;
        mState.rangeEnd = p.end;
        mState.seekSerial = p.seekSerial;
        mState.rangeMode = std::uint8_t(p.range);
        mState.paused = p.paused;
        mState.chapter = session.chapterIndex();
        mLeaderT->publish(wall::encode(mState));
        mBarrier->begin(mState.frame, monotonicSeconds(),
                        mState.frame == 1 ? kJoinSeconds : mScreen.wall.sync.deadlineMs / 1000.0);
        return true;
    }
    const double until = monotonicSeconds() + maxWait;
    for (;;) {
        drain();  // the newest state wins: read everything queued before choosing
        const double now = monotonicSeconds();
        if (auto s = mFollower->takeStateToDraw()) {
            mState = std::move(*s);
            mReadySent = false;
            mWarnedSilent = false;
            if (mState.scenarioHash != hashOf(session) && mWarnedHash != mState.scenarioHash) {
                mWarnedHash = mState.scenarioHash;
                KIOSK_LOG_WARN(
                    kTag,
                    "screen %s: the leader plays a different %s (content differs); drawing ours",
                    mScreen.self().id.c_str(), mState.scenarioId.c_str());
            }
            return true;
        }
        if (mFollower->stopped()) return false;
        if (mFollower->leaderSilent(now) && !mWarnedSilent) {
            mWarnedSilent = true;
            KIOSK_LOG_WARN(kTag,
                           "screen %s: no word from the leader for %.0f s; keeping the last frame",
                           mScreen.self().id.c_str(), kLeaderSilentSeconds);
        }
        if (now >= until) return false;
        const auto wait = std::chrono::microseconds(std::int64_t((until - now) * 1e6));
        if (auto m = mFollowerT->receive(std::min(wait, std::chrono::microseconds(20000))))
            handle(*m, monotonicSeconds());
    }
}

bool WallNode::barrier(Session& session, const std::function<void()>& redraw) {
    return isLeader() ? leaderBarrier(session, redraw) : followerBarrier(session, redraw);
}

bool WallNode::leaderBarrier(Session& session, const std::function<void()>& redraw) {
    bool ownReady = false;
    double readyAt = 0;
    double lastPublish = monotonicSeconds();
    for (;;) {
        const double now = monotonicSeconds();
        if (!ownReady) {
            if (session.terrain().settled()) {
                glFinish();  // "ready" means drawn: the swap is then only the present
                ownReady = true;
                readyAt = monotonicSeconds();
                mBarrier->leaderReady(session.terrain().frameInfo().wantedSequenceResident);
            } else if (now < mBarrier->deadline()) {
                redraw();  // loads what arrived; the frame is complete once nothing is missing
            }
        }
        if (mBarrier->releasable(monotonicSeconds())) break;
        if (mState.frame == 1 && now - lastPublish > kRepublishSeconds) {
            mLeaderT->publish(wall::encode(mState));
            lastPublish = now;
        }
        while (auto m = mLeaderT->receive(std::chrono::microseconds(1000))) {
            if (auto r = wall::decodeReady(*m)) {
                if (r->scenarioHash != mState.scenarioHash && r->frame == mState.frame &&
                    mWarnedHash != r->scenarioHash) {
                    mWarnedHash = r->scenarioHash;
                    KIOSK_LOG_WARN(kTag, "screen %s plays a different scenario than the leader",
                                   r->screen < mScreen.wall.screens.size()
                                       ? mScreen.wall.screens[r->screen].id.c_str()
                                       : "?");
                }
                mBarrier->onReady(*r);
            }
            if (mBarrier->releasable(monotonicSeconds())) break;
        }
    }
    mLastRelease = mBarrier->release();
    // How long the wall waited for others after this node was ready (the barrier's stall).
    mWaitUs = ownReady ? (monotonicSeconds() - readyAt) * 1e6 : 0.0;
    for (auto s : mBarrier->lastDropped())
        KIOSK_LOG_WARN(
            kTag,
            "frame %llu: screen %s missed the %.0f ms deadline; dropped until it reports again",
            static_cast<unsigned long long>(mState.frame), mScreen.wall.screens[s].id.c_str(),
            mScreen.wall.sync.deadlineMs);
    mLeaderT->publish(wall::encode(mLastRelease));
    mStepResident = mBarrier->stepResident();
    if (mStepResident) mStepTime = mState.dataTime;  // every node has it: the next frame shows it
    return true;
}

bool WallNode::followerBarrier(Session& session, const std::function<void()>& redraw) {
    for (;;) {
        const double now = monotonicSeconds();
        if (mFollower->stopped()) return false;
        if (mFollower->swapDue()) return true;
        if (mFollower->leaderSilent(now)) return false;
        const bool resident = session.terrain().settled();
        if (resident && mFollower->pendingFrame() && !mReadySent)
            glFinish();  // drawn, not just queued
        if (auto r = mFollower->drawn(
                resident, session.terrain().frameInfo().wantedSequenceResident, hashOf(session))) {
            mFollowerT->send(wall::encode(*r));
            mReadySent = true;
        } else if (!resident) {
            redraw();
        }
        // The newest state wins: if the leader moved on (we were dropped), draw the new one.
        if (auto m = mFollowerT->receive(std::chrono::microseconds(1000))) {
            handle(*m, monotonicSeconds());
            drain();
            if (mFollower->swapDue()) return true;  // swap what we drew, then catch up
            if (mFollower->hasNewerState()) return false;
        }
    }
}

void WallNode::swapped(const scene::SceneFrameInfo& info) {
    std::uint64_t frame = mState.frame;
    if (mFollower) frame = mFollower->swapped();
    if (!mLog) return;
    const double us = std::chrono::duration<double, std::micro>(
                          std::chrono::steady_clock::now().time_since_epoch())
                          .count();
    std::fprintf(
        mLog,
        "{\"screen\":\"%s\",\"frame\":%llu,\"data_time\":%.6f,\"step_time\":%.6f,\"step\":[%d,%d],"
        "\"holding\":%s,\"swap_us\":%.0f",
        mScreen.self().id.c_str(), static_cast<unsigned long long>(frame), mState.dataTime,
        mState.stepTime, info.shownFrameA, info.shownFrameB,
        info.holdingSequence ? "true" : "false", us);
    if (isLeader())
        std::fprintf(mLog, ",\"ready_nodes\":%u,\"by_deadline\":%s,\"wait_us\":%.0f",
                     mLastRelease.readyNodes, mLastRelease.byDeadline ? "true" : "false", mWaitUs);
    std::fputs("}\n", mLog);
    std::fflush(mLog);
}

void WallNode::stop() {
    if (mLeaderT) mLeaderT->publish(wall::encodeStop());
}

}  // namespace kiosk::app
