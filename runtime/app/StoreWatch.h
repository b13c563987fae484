#pragma once

#include "config/Scenario.h"

#include <cstdint>
#include <filesystem>
#include <future>
#include <optional>
#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief Watches the stores of the scenario on screen for a nightly model run replacing one by
 * atomic rename. A changed file (another inode, size or mtime) is opened and checked on a
 * background thread; when it passes, swapReady() asks the frame loop to re-open the scenario at
 * the next step boundary. A broken replacement is logged once and the old picture stays. A
 * deleted store keeps the picture (SQLite still reads the open, unlinked file) and reports
 * degraded until the file is back. Render thread only (the check runs on its own thread).
 */
class StoreWatch {
public:
    ~StoreWatch();
    /** @brief Start watching the stores of a newly opened scenario (forgets the previous one). */
    void watch(const config::Scenario& scenario);
    /** @brief Look at the files (at most once per second); call once per frame. */
    void poll(double now);
    /** @brief A validated replacement is waiting to be taken. */
    bool swapReady() const noexcept { return mSwapReady; }
    /** @brief A store file is missing: the picture is kept from the open file. */
    bool degraded() const noexcept { return !mDegradedWhy.empty(); }
    const std::string& degradedWhy() const noexcept { return mDegradedWhy; }
    /** @brief Store files being watched with their inode (for /health). */
    std::vector<std::pair<std::string, std::uint64_t>> files() const;

private:
    struct Stamp {
        std::uint64_t dev = 0, ino = 0, size = 0;
        std::int64_t mtimeNs = 0;
        bool operator==(const Stamp&) const = default;
    };
    struct Store {
        std::filesystem::path path;
        Stamp shown;                    ///< the file the open session reads
        std::optional<Stamp> rejected;  ///< a replacement that failed its check (logged once)
        bool missing = false;
    };
    static std::optional<Stamp> stampOf(const std::filesystem::path& p);
    void finishCheck();

    std::vector<Store> mStores;
    double mLastPoll = -1e300;
    bool mSwapReady = false;
    std::string mDegradedWhy;
    // The background check of one replacement at a time.
    std::future<std::string> mCheck;  ///< empty string: passed, else why it failed
    std::size_t mCheckIndex = 0;
    Stamp mCheckStamp;
};

}  // namespace kiosk::app
