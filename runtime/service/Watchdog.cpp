#include "runtime/service/Watchdog.h"

#include <cstdlib>
#include <systemd/sd-daemon.h>

namespace kiosk::service {

WatchdogPacer::Due WatchdogPacer::frameCompleted(double now) noexcept {
    Due due;
    if (!mReadySent) {
        due.ready = true;
        mReadySent = true;
    }
    pace(due, now);
    return due;
}

WatchdogPacer::Due WatchdogPacer::holding(double now) noexcept {
    Due due;
    pace(due, now);
    return due;
}

void WatchdogPacer::pace(Due& due, double now) noexcept {
    if (mWatchdogUsec > 0 && now - mLastPing >= pingInterval()) {
        due.watchdog = true;
        mLastPing = now;
    }
    if (due.ready || now - mLastStatus >= 1.0) {
        due.status = true;
        mLastStatus = now;
    }
}

SdNotifier::SdNotifier() {
    const char* socket = std::getenv("NOTIFY_SOCKET");
    mEnabled = socket && *socket;
    if (!mEnabled) return;
    std::uint64_t usec = 0;
    // unset_environment = 0: a child (none today) may still see it; >0 means the watchdog is on
    // and WATCHDOG_PID (if set) names this process.
    if (sd_watchdog_enabled(0, &usec) > 0) mWatchdogUsec = usec;
}

bool SdNotifier::send(const std::string& message) const {
    if (!mEnabled) return true;
    return sd_notify(0, message.c_str()) > 0;
}

}  // namespace kiosk::service
