#include "runtime/app/ScenarioReloader.h"

#include "runtime/app/Session.h"

#include <algorithm>
#include <chrono>

namespace kiosk::app {

ScenarioReloader::Target ScenarioReloader::targetOf(std::filesystem::path path,
                                                    std::vector<std::filesystem::path> files) {
    if (std::find(files.begin(), files.end(), path) == files.end())
        files.insert(files.begin(), path);
    Target t{std::move(path), std::move(files), {}};
    t.stamps = stampsOf(t.files);
    return t;
}

ScenarioReloader::ScenarioReloader(std::filesystem::path scenarioPath,
                                   std::vector<std::filesystem::path> files, double pollSeconds)
    : mPollSeconds(pollSeconds), mTarget(targetOf(std::move(scenarioPath), std::move(files))) {
    mThread = std::thread([this] { run(); });
}

ScenarioReloader::~ScenarioReloader() {
    {
        std::lock_guard lock(mMutex);
        mStop = true;
    }
    mWake.notify_all();
    // A load in progress finishes first (the reader is bounded by config/Limits.h).
    mThread.join();
}

void ScenarioReloader::watch(std::filesystem::path scenarioPath,
                             std::vector<std::filesystem::path> files) {
    // Stamps now, on the caller's thread: the session it just opened read these versions.
    Target next = targetOf(std::move(scenarioPath), std::move(files));
    {
        std::lock_guard lock(mMutex);
        mNextTarget = std::move(next);
        ++mGeneration;
        mFinished.reset();
        mForce = false;
    }
    mWake.notify_all();
}

void ScenarioReloader::requestLoad() {
    {
        std::lock_guard lock(mMutex);
        mForce = true;
    }
    mWake.notify_all();
}

std::optional<ScenarioReloader::Loaded> ScenarioReloader::take() {
    std::lock_guard lock(mMutex);
    std::optional<Loaded> out = std::move(mFinished);
    mFinished.reset();
    return out;
}

ScenarioReloader::Stamps ScenarioReloader::stampsOf(
    const std::vector<std::filesystem::path>& files) {
    Stamps out;
    out.reserve(files.size());
    for (const auto& f : files) {
        std::error_code ec;
        out.push_back(std::filesystem::last_write_time(f, ec));
        if (ec) out.back() = std::filesystem::file_time_type::min();  // missing: may appear
    }
    return out;
}

void ScenarioReloader::run() {
    for (;;) {
        bool force = false;
        std::uint64_t generation = 0;
        {
            std::unique_lock lock(mMutex);
            mWake.wait_for(lock, std::chrono::duration<double>(mPollSeconds),
                           [this] { return mStop || mForce || mNextTarget; });
            if (mStop) return;
            if (mNextTarget) {
                mTarget = std::move(*mNextTarget);
                mNextTarget.reset();
            }
            force = mForce;
            mForce = false;
            generation = mGeneration;
        }
        // Stamps are taken before loading: an edit saved while a (slow) load runs is seen at
        // the next poll instead of being taken for part of what was loaded.
        Stamps before = stampsOf(mTarget.files);
        if (!force && before == mTarget.stamps) continue;
        ++mLoads;
        Loaded loaded = Session::readChecked(mTarget.path);
        // Watch what this load read; files new to the list count as unseen (stamp min), so an
        // edit to them during the load triggers one more load rather than being lost. A broken
        // edit keeps the old list, so fixing it is noticed.
        std::vector<std::filesystem::path> files =
            loaded ? (*loaded.value)->sourceFiles : mTarget.files;
        if (std::find(files.begin(), files.end(), mTarget.path) == files.end())
            files.insert(files.begin(), mTarget.path);
        Stamps stamps;
        for (const auto& f : files) {
            auto it = std::find(mTarget.files.begin(), mTarget.files.end(), f);
            stamps.push_back(it != mTarget.files.end()
                                 ? before[std::size_t(it - mTarget.files.begin())]
                                 : std::filesystem::file_time_type::min());
        }
        mTarget.files = std::move(files);
        mTarget.stamps = std::move(stamps);
        std::lock_guard lock(mMutex);
        // play switched to another scenario meanwhile: this result is not for the screen.
        if (generation == mGeneration) mFinished = std::move(loaded);
    }
}

}  // namespace kiosk::app
