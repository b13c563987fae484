#pragma once

#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Args.h"
#include "runtime/app/KioskPlaylist.h"
#include "runtime/app/StoreWatch.h"
#include "runtime/core/Result.h"
#include "runtime/gl/Context.h"
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
    static std::unique_ptr<KioskHooks> create(const Args& args, const std::filesystem::path& file,
                                              int& exitCode);

    /**
     * @brief The first session: the scenario `file`, or for a kiosk file its first playable
     * entry. Failure diagnostics name the file (exit 1).
     */
    Result<std::unique_ptr<Session>> openFirst(const gl::Caps& caps);
    /**
     * @brief The session to switch to, else nullptr (keep the current one): for playlists the
     * next playable entry when the one on screen is done or next/previous was requested; for a
     * store replaced on disk (StoreWatch) the same scenario re-opened at a step boundary.
     */
    std::unique_ptr<Session> nextSession(const anim::ScenarioClock& clock, const gl::Caps& caps);
    /** @brief The last switch re-opened the same scenario (store swap): keep the data time. */
    bool keepsDataTime() const noexcept { return mKeepTime; }
    /** @brief The scenario on screen opened again (hot reload, control, store swap), with the
     * kiosk file's budgets. */
    Result<std::unique_ptr<Session>> reopen(const gl::Caps& caps);
    /**
     * @brief The scenario on screen from a reload play's worker finished (ScenarioReloader):
     * its diagnostics if it was refused, else the GL half built here with the kiosk file's
     * budgets (warnings logged).
     */
    Result<std::unique_ptr<Session>> adopt(Result<std::unique_ptr<config::Scenario>> loaded,
                                           const gl::Caps& caps);
    /** @brief Scenario file on screen (the one hot reload watches). */
    std::filesystem::path currentScenario() const;
    /** @brief Fade curtain for this frame (0 without a playlist fade). */
    float curtain() const;

    /** @brief What the frame loop must do besides the clock changes already applied. */
    struct Requests {
        bool reload = false;                  ///< re-open the scenario now
        int playlistStep = 0;                 ///< +1 next entry, -1 previous
        bool clock = false;                   ///< pause/play/seek/rate acted on the clock
        std::vector<service::LensMove> lens;  ///< lens moves, in order (app/LensControl.h)
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
    std::unique_ptr<KioskPlaylist> mPlaylist;
    std::filesystem::path mFile;
    std::filesystem::path mStallFile;
    int mPendingStep = 0;
    StoreWatch mStores;
    const Session* mWatched = nullptr;  ///< session whose stores mStores watches
    /// session of the previous frame (compared only, never dereferenced: it may be gone)
    const Session* mLastDrawn = nullptr;
    bool mAtStepBoundary = true;  ///< the shown sequence step changed (or none, paused)
    std::int32_t mLastShownFrame = -2;
    bool mKeepTime = false;
    double mRetryAt = 0;  ///< after a failed switch, the next attempt (monotonic seconds)
};

}  // namespace kiosk::app
