#include "runtime/app/ScenarioReloader.h"

#include "runtime/app/Session.h"

#include <algorithm>
#include <chrono>

namespace kiosk::app {

ScenarioReloader::ScenarioReloader(std::filesystem::path scenarioPath,
                                   std::vector<std::filesystem::path> files, double pollSeconds)
    : mPath(std::move(scenarioPath)), mPollSeconds(pollSeconds), mFiles(std::move(files)) {
    if (mFiles.empty()) mFiles.push_back(mPath);
    mStamps = stampsOf(mFiles);
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
        {
            std::unique_lock lock(mMutex);
            mWake.wait_for(lock, std::chrono::duration<double>(mPollSeconds),
                           [this] { return mStop; });
            if (mStop) return;
        }
        // Stamps are taken before loading: an edit saved while a (slow) load runs is seen at
        // the next poll instead of being taken for part of what was loaded.
        Stamps before = stampsOf(mFiles);
        if (before == mStamps) continue;
        ++mLoads;
        Loaded loaded = Session::readChecked(mPath);
        // Watch what this load read; files new to the list count as unseen (stamp min), so an
        // edit to them during the load triggers one more load rather than being lost.
        std::vector<std::filesystem::path> files;
        if (loaded) {
            files = (*loaded.value)->sourceFiles;
        } else {
            // A broken edit: keep watching what was read, so fixing it is noticed.
            files = mFiles;
        }
        if (std::find(files.begin(), files.end(), mPath) == files.end())
            files.insert(files.begin(), mPath);
        Stamps stamps;
        for (const auto& f : files) {
            auto it = std::find(mFiles.begin(), mFiles.end(), f);
            stamps.push_back(it != mFiles.end() ? before[std::size_t(it - mFiles.begin())]
                                                : std::filesystem::file_time_type::min());
        }
        mFiles = std::move(files);
        mStamps = std::move(stamps);
        std::lock_guard lock(mMutex);
        mFinished = std::move(loaded);
    }
}

}  // namespace kiosk::app
