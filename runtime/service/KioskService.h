#pragma once

#include "runtime/service/Control.h"
#include "runtime/service/HttpServer.h"
#include "runtime/service/ServiceState.h"
#include "runtime/service/Watchdog.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kiosk::service {

struct ServiceOptions {
    std::optional<ListenAddress> listen;             ///< no HTTP server without it
    std::optional<std::filesystem::path> tokenFile;  ///< control disabled (403) without it
    /** @brief /health reports 503 after this long without a completed frame. */
    double stallSeconds = 5.0;
};

/**
 * @brief Everything the outside world sees of a running kiosk: systemd notify/watchdog and the
 * HTTP endpoints. The frame loop owns it: fills snapshot(), then frameCompleted() once per
 * frame, and applies what takeControl() returns. Render thread only, except the HTTP server's
 * own thread, which sees nothing but the published copy and the control queue.
 */
class KioskService {
public:
    /** @brief Start the server (if asked); nullptr with `why` (a usage or bind error). */
    static std::unique_ptr<KioskService> start(const ServiceOptions& options, std::string& why);
    ~KioskService();

    /** @brief The frame loop's working snapshot; published by frameCompleted(). */
    ServiceSnapshot& snapshot() noexcept { return mSnap; }
    /**
     * @brief One frame is on screen: record its time, publish the snapshot, and send READY
     * (first frame), WATCHDOG (paced) and STATUS to systemd.
     */
    void frameCompleted(double frameMs);
    /**
     * @brief No frame this iteration, on purpose: `why` names the cause for /health and STATUS;
     * the watchdog keeps being fed because the loop is alive. Cleared by the next frameCompleted().
     */
    void holding(const std::string& why);
    /** @brief Control commands received since the last call (HTTP thread -> frame loop). */
    const std::vector<ControlCommand>& takeControl();
    /** @brief Tell systemd the kiosk is stopping (STOPPING=1). */
    void stopping();
    int httpPort() const noexcept { return mHttp ? mHttp->port() : 0; }
    bool notifyEnabled() const noexcept { return mNotifier.enabled(); }

private:
    KioskService() = default;
    std::string statusLine() const;
    void notify(const WatchdogPacer::Due& due);

    ServiceSnapshot mSnap;
    SnapshotBox mBox;
    ControlQueue mControl;
    std::vector<ControlCommand> mTaken;
    SdNotifier mNotifier;
    WatchdogPacer mPacer;
    std::unique_ptr<HttpServer> mHttp;
    double mFpsWindowStart = -1;
    std::uint64_t mFpsWindowFrames = 0;
};

/** @brief Monotonic seconds (steady clock), the time base of snapshots and /health. */
double monotonicSeconds() noexcept;

}  // namespace kiosk::service
