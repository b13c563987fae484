#pragma once

#include "config/Scenario.h"
#include "runtime/core/Result.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

// play's hot reload, off the frame loop. A worker polls the scenario's files; when one changed it
// reads and checks the scenario (Session::readChecked: the part a hostile edit can make slow)
// and hands the finished result over. The frame loop only ever takes a finished result: an
// include bomb saved into a running kiosk costs the worker, never a frame.
namespace kiosk::app {

class ScenarioReloader {
public:
    using Loaded = Result<std::unique_ptr<config::Scenario>>;

    /**
     * @brief Start watching `files` (the running scenario's sourceFiles; `scenarioPath` first)
     * as they are now. Polls every `pollSeconds`.
     */
    ScenarioReloader(std::filesystem::path scenarioPath, std::vector<std::filesystem::path> files,
                     double pollSeconds = 0.5);
    ~ScenarioReloader();
    ScenarioReloader(const ScenarioReloader&) = delete;
    ScenarioReloader& operator=(const ScenarioReloader&) = delete;

    /**
     * @brief From now on watch another scenario (play switched session: playlist entry, store
     * swap), its files as they are now. A load of the previous one still running is dropped when
     * it finishes; an untaken result is dropped now. Never waits for the worker.
     */
    void watch(std::filesystem::path scenarioPath, std::vector<std::filesystem::path> files);
    /** @brief Load the watched scenario at the next chance even if no file changed (control). */
    void requestLoad();

    /** @brief A load finished since the last call (valid or not); never blocks. Frame loop. */
    std::optional<Loaded> take();

    /** @brief Loads started so far (tests). */
    int loadsStarted() const noexcept { return mLoads.load(); }

private:
    using Stamps = std::vector<std::filesystem::file_time_type>;
    static Stamps stampsOf(const std::vector<std::filesystem::path>& files);
    void run();

    struct Target {
        std::filesystem::path path;
        std::vector<std::filesystem::path> files;
        Stamps stamps;
    };
    static Target targetOf(std::filesystem::path path, std::vector<std::filesystem::path> files);

    const double mPollSeconds;
    Target mTarget;  // worker only (set before the worker starts, then from mNextTarget)

    std::mutex mMutex;
    std::condition_variable mWake;
    bool mStop = false;                 // guarded by mMutex
    bool mForce = false;                // guarded by mMutex
    std::optional<Target> mNextTarget;  // guarded by mMutex; watch() hands it to the worker
    std::uint64_t mGeneration = 0;      // guarded by mMutex; results of older ones are dropped
    std::optional<Loaded> mFinished;    // guarded by mMutex; a newer result replaces an untaken one
    std::atomic<int> mLoads{0};
    std::thread mThread;
};

}  // namespace kiosk::app
