#include "runtime/app/KioskPlaylist.h"

#include "runtime/app/Session.h"
#include "runtime/core/Log.h"
#include "runtime/service/KioskService.h"

#include <ctime>

namespace kiosk::app {
namespace {
constexpr const char* kTag = "playlist";
}

KioskPlaylist::KioskPlaylist(config::KioskFile file) : mFile(std::move(file)) {
    for (const auto& e : mFile.playlist) {
        service::PlaylistRule r;
        r.durationSeconds = e.durationSeconds.value_or(0);
        r.loops = e.loops.value_or(0);
        if (e.window) {
            r.hasWindow = true;
            r.windowFrom = e.window->fromSeconds;
            r.windowTo = e.window->toSeconds;
        }
        mRules.push_back(r);
    }
    mBroken.assign(mRules.size(), false);
    mBrokenWhy.assign(mRules.size(), {});
}

std::unique_ptr<Session> KioskPlaylist::open(int step, const gl::Caps& caps, Diagnostics& errors) {
    const int tod = service::localSecondOfDay(double(std::time(nullptr)));
    // A new pass over the list: entries broken last time get another chance.
    std::vector<bool> tried(mRules.size(), false);
    int from = mIndex;
    bool includeFrom = step == 0;
    const int dir = step < 0 ? -1 : 1;
    for (std::size_t attempt = 0; attempt < mRules.size(); ++attempt) {
        const int i = service::pickEntry(mRules, from, dir, tod, tried, includeFrom);
        if (i < 0) break;
        tried[i] = true;
        const config::KioskEntry& e = mFile.playlist[i];
        auto opened =
            Session::open(e.scenario, caps, [this](config::Scenario& s) { applyBudgets(s); });
        if (opened) {
            if (mBroken[i]) KIOSK_LOG_INFO(kTag, "%s: entry %d plays again", e.scenario.c_str(), i);
            mBroken[i] = false;
            mBrokenWhy[i].clear();
            mIndex = i;
            mEntryStart = service::monotonicSeconds();
            KIOSK_LOG_INFO(kTag, "entry %d/%d: %s", i + 1, size(), e.scenario.c_str());
            return std::move(*opened.value);
        }
        const Diagnostic* d = opened.diagnostics.firstError();
        const std::string why = d ? d->format() : "cannot be opened";
        // One log line per entry and distinct problem, not one per pass.
        if (why != mBrokenWhy[i])
            KIOSK_LOG_ERROR(kTag, "skipping %s entry %d: %s", e.pointer.c_str(), i, why.c_str());
        mBroken[i] = true;
        mBrokenWhy[i] = why;
        ++mSkipped;
        errors = opened.diagnostics;
        from = i;
        includeFrom = false;
    }
    return nullptr;
}

void KioskPlaylist::applyBudgets(config::Scenario& s) const {
    if (mFile.cacheBytes) s.terrain.cacheBytes = *mFile.cacheBytes;
    if (mFile.gpuBytes) s.terrain.gpuBytes = *mFile.gpuBytes;
    s.memoryBudgets = mFile.memory;  // LUTs, mapping arrays, font atlas (Session enforces)
}

Result<std::unique_ptr<Session>> KioskPlaylist::reopen(const gl::Caps& caps) const {
    return Session::open(currentScenario(), caps, [this](config::Scenario& s) { applyBudgets(s); });
}

Result<std::unique_ptr<Session>> KioskPlaylist::create(std::unique_ptr<config::Scenario> scenario,
                                                       const gl::Caps& caps) const {
    return Session::create(std::move(scenario), caps,
                           [this](config::Scenario& s) { applyBudgets(s); });
}

bool KioskPlaylist::finished(const anim::ScenarioClock& clock) const {
    service::EntryProgress p;
    p.wallSeconds = service::monotonicSeconds() - mEntryStart;
    p.loops = clock.loops();
    p.clockAtEnd = clock.rangeMode() == anim::RangeMode::Clamp && clock.rate() > 0 &&
                   clock.current() >= clock.end();
    const int tod = service::localSecondOfDay(double(std::time(nullptr)));
    return service::entryFinished(mRules[mIndex], p, tod);
}

float KioskPlaylist::curtain() const {
    if (mFile.transition != config::TransitionKind::Fade) return 0.0f;
    const double since = service::monotonicSeconds() - mEntryStart;
    std::optional<double> until;
    if (mRules[mIndex].durationSeconds > 0) until = mRules[mIndex].durationSeconds - since;
    return service::fadeAlpha(since, until, mFile.transitionSeconds);
}

std::vector<std::string> KioskPlaylist::warnings() const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < mBroken.size(); ++i)
        if (mBroken[i])
            out.push_back("skipped " + mFile.playlist[i].pointer + ": " + mBrokenWhy[i]);
    return out;
}

}  // namespace kiosk::app
