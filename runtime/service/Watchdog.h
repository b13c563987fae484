#pragma once

#include <cstdint>
#include <memory>
#include <string>

// systemd notify protocol (sd_notify(3)): READY=1 after the first complete frame, WATCHDOG=1
// from the frame loop itself, STATUS= lines. The pacing is pure logic (tested without systemd);
// SdNotifier is the thin libsystemd transport.
namespace kiosk::service {

/**
 * @brief Decides when the frame loop sends READY and WATCHDOG. Called only from the frame loop
 * after a frame completed, so a stuck swap, loader deadlock or GPU hang stops the pings: there is
 * no timer that pings on its own. Pings go out at half the watchdog interval (systemd's advice),
 * STATUS at most once per second.
 */
class WatchdogPacer {
public:
    /** @param watchdogUsec WATCHDOG_USEC (0: watchdog off). */
    explicit WatchdogPacer(std::uint64_t watchdogUsec = 0) : mWatchdogUsec(watchdogUsec) {}

    struct Due {
        bool ready = false;     ///< send READY=1 (once, after the first frame)
        bool watchdog = false;  ///< send WATCHDOG=1
        bool status = false;    ///< send a fresh STATUS=
    };
    /** @brief A frame completed at monotonic time `now` (seconds). */
    Due frameCompleted(double now) noexcept;
    /**
     * @brief The loop is alive but keeps its last frame on purpose (a wall follower waiting for a
     * silent leader): WATCHDOG and STATUS as paced, never READY. A restart would not bring the
     * leader back and would drop the frame on screen.
     */
    Due holding(double now) noexcept;

    double pingInterval() const noexcept { return double(mWatchdogUsec) * 1e-6 / 2.0; }
    bool watchdogEnabled() const noexcept { return mWatchdogUsec > 0; }

private:
    void pace(Due& due, double now) noexcept;

    std::uint64_t mWatchdogUsec;
    bool mReadySent = false;
    double mLastPing = -1e300;
    double mLastStatus = -1e300;
};

/** @brief sd_notify transport; silent (all calls no-ops) when NOTIFY_SOCKET is unset. */
class SdNotifier {
public:
    /** @brief Reads NOTIFY_SOCKET and WATCHDOG_USEC (sd_watchdog_enabled) from the environment. */
    SdNotifier();
    bool enabled() const noexcept { return mEnabled; }
    std::uint64_t watchdogUsec() const noexcept { return mWatchdogUsec; }
    /** @brief Send one notify message ("READY=1\nSTATUS=..."); false if sending failed. */
    bool send(const std::string& message) const;

private:
    bool mEnabled = false;
    std::uint64_t mWatchdogUsec = 0;
};

}  // namespace kiosk::service
