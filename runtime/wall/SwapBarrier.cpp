#include "runtime/wall/SwapBarrier.h"

namespace kiosk::wall {

SwapBarrier::SwapBarrier(std::vector<std::uint32_t> screens, double deadlineSeconds)
    : mDeadlineSeconds(deadlineSeconds) {
    for (auto s : screens) mFollowers.push_back(Follower{s});
}

SwapBarrier::Follower* SwapBarrier::find(std::uint32_t screen) {
    for (auto& f : mFollowers)
        if (f.screen == screen) return &f;
    return nullptr;
}

void SwapBarrier::begin(std::uint64_t frame, double now, double waitSeconds) {
    mFrame = frame;
    mDeadline = now + waitSeconds;
    mOpen = true;
    mLeaderReady = mLeaderStep = false;
    for (auto& f : mFollowers) {
        if (f.rejoin) f.member = true;
        f.rejoin = false;
        f.ready = f.stepResident = false;
    }
}

void SwapBarrier::leaderReady(bool stepResident) {
    mLeaderReady = true;
    mLeaderStep = stepResident;
}

void SwapBarrier::onReady(const Ready& r) {
    Follower* f = find(r.screen);
    if (!f) return;
    if (mOpen && r.frame == mFrame) {
        // A dropped node that caught up with the open frame is back at once.
        f->member = true;
        f->ready = true;
        f->stepResident = r.stepResident;
        return;
    }
    if (!f->member) f->rejoin = true;
}

bool SwapBarrier::releasable(double now) const {
    if (!mOpen) return false;
    if (now >= mDeadline) return true;
    if (!mLeaderReady) return false;
    for (const auto& f : mFollowers)
        if (f.member && !f.ready) return false;
    return true;
}

Release SwapBarrier::release() {
    Release r;
    r.frame = mFrame;
    mDropped.clear();
    bool step = mLeaderReady && mLeaderStep;
    std::uint32_t ready = mLeaderReady ? 1u : 0u;
    for (auto& f : mFollowers) {
        if (f.ready) {
            ++ready;
            step = step && f.stepResident;
        } else if (f.member) {
            f.member = false;  // missed the deadline: not waited for until it reports again
            mDropped.push_back(f.screen);
        }
    }
    r.byDeadline = !mDropped.empty() || !mLeaderReady;
    r.readyNodes = ready;
    mStepResident = step;
    mOpen = false;
    return r;
}

std::size_t SwapBarrier::members() const {
    std::size_t n = 0;
    for (const auto& f : mFollowers) n += f.member ? 1u : 0u;
    return n;
}

bool SwapBarrier::isMember(std::uint32_t screen) const {
    for (const auto& f : mFollowers)
        if (f.screen == screen) return f.member;
    return false;
}

}  // namespace kiosk::wall
