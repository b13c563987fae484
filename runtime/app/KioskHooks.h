#pragma once

#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Args.h"
#include "runtime/service/KioskService.h"

#include <filesystem>
#include <memory>
#include <string>

namespace kiosk::app {

class Session;

/**
 * @brief What `play` does for unattended operation, kept out of the frame loop's file: builds
 * the kiosk service from `--listen` / `--token-file`, fills its snapshot from the session after
 * each frame, and applies remote control commands to the clock. Render thread only.
 */
class KioskHooks {
public:
    /** @brief The value options `play` accepts for this (added to its Args). */
    static const std::vector<std::string>& optionNames();
    /**
     * @brief From parsed arguments; nullptr on a usage error (exit 2, message printed) or when
     * the server cannot start (exit 3).
     */
    static std::unique_ptr<KioskHooks> create(const Args& args, int& exitCode);

    /** @brief What the frame loop must do besides the clock changes already applied. */
    struct Requests {
        bool reload = false;   ///< re-open the scenario now
        int playlistStep = 0;  ///< +1 next entry, -1 previous
    };
    /** @brief Take the queued control commands; pause/play/seek/rate act on `clock` here. */
    Requests applyControl(anim::ScenarioClock& clock);

    /** @brief A frame is on screen: publish what it showed (and ping systemd). */
    void frameDone(Session& session, const anim::ScenarioClock& clock,
                   const std::filesystem::path& scenario, double frameMs, double dataTime);
    /** @brief A reload (scenario edit, control request, store swap) was taken or refused. */
    void noteReload(bool ok);

    /**
     * @brief Test hook: while the file named by GEOKIOSK_TEST_STALL_FILE exists the frame loop
     * stops here (as a hung swap would), so tests can watch the watchdog and /health react.
     * Returns early on SIGTERM.
     */
    void stallWhileTestFileExists();

    service::KioskService& service() noexcept { return *mService; }

private:
    std::unique_ptr<service::KioskService> mService;
    std::filesystem::path mStallFile;
};

}  // namespace kiosk::app
