#include "runtime/service/KioskService.h"

#include "runtime/core/Log.h"
#include "runtime/core/TimeParse.h"

#include <chrono>
#include <cstdio>

namespace kiosk::service {
namespace {
constexpr const char* kTag = "service";
}

double monotonicSeconds() noexcept {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

std::unique_ptr<KioskService> KioskService::start(const ServiceOptions& options, std::string& why) {
    std::unique_ptr<KioskService> s(new KioskService());
    s->mPacer = WatchdogPacer(s->mNotifier.watchdogUsec());
    s->mSnap.startedAt = monotonicSeconds();
    s->mBox.publish(s->mSnap);
    s->mTaken.reserve(ControlQueue::kMaxPending);
    TokenGuard token;
    if (options.tokenFile) {
        auto t = TokenGuard::fromFile(*options.tokenFile, why);
        if (!t) return nullptr;
        token = std::move(*t);
    }
    if (options.listen) {
        HttpEndpoints ep;
        ep.snapshots = &s->mBox;
        ep.control = &s->mControl;
        ep.token = std::move(token);
        ep.stallSeconds = options.stallSeconds;
        ep.now = monotonicSeconds;
        s->mHttp = std::make_unique<HttpServer>();
        if (!s->mHttp->start(*options.listen, std::move(ep), why)) return nullptr;
        KIOSK_LOG_INFO(kTag, "listening on %s:%d (/health, /metrics, /control %s)",
                       options.listen->host.c_str(), s->mHttp->port(),
                       options.tokenFile ? "enabled" : "disabled: no token file");
    }
    if (s->mNotifier.enabled())
        KIOSK_LOG_INFO(kTag, "systemd notify on; watchdog %s",
                       s->mPacer.watchdogEnabled()
                           ? (std::to_string(s->mNotifier.watchdogUsec() / 1000) + " ms").c_str()
                           : "off");
    return s;
}

KioskService::~KioskService() {
    if (mHttp) mHttp->stop();
}

void KioskService::frameCompleted(double frameMs) {
    const double now = monotonicSeconds();
    mSnap.frames++;
    mSnap.frameMs.observe(kFrameMsBuckets, frameMs);
    mSnap.lastFrameAt = now;
    mSnap.holding.clear();
    if (mFpsWindowStart < 0) mFpsWindowStart = now;
    ++mFpsWindowFrames;
    if (now - mFpsWindowStart >= 1.0) {
        mSnap.fps = double(mFpsWindowFrames) / (now - mFpsWindowStart);
        mFpsWindowStart = now;
        mFpsWindowFrames = 0;
    }
    mBox.publish(mSnap);
    if (mNotifier.enabled()) notify(mPacer.frameCompleted(now));
}

void KioskService::holding(const std::string& why) {
    if (mSnap.holding != why) {
        mSnap.holding = why;
        mBox.publish(mSnap);
    }
    if (mNotifier.enabled()) notify(mPacer.holding(monotonicSeconds()));
}

void KioskService::notify(const WatchdogPacer::Due& due) {
    std::string msg;
    if (due.ready) msg += "READY=1\n";
    if (due.watchdog) msg += "WATCHDOG=1\n";
    if (due.status) msg += "STATUS=" + statusLine() + "\n";
    if (!msg.empty() && !mNotifier.send(msg))
        KIOSK_LOG_WARN(kTag, "sd_notify failed (NOTIFY_SOCKET unreachable?)");
}

std::string KioskService::statusLine() const {
    char fps[32];
    std::snprintf(fps, sizeof fps, "%.1f fps", mSnap.fps);
    std::string line = mSnap.scenario + ", data " + formatIso8601(mSnap.dataTime) + ", " + fps;
    std::string degraded;
    for (const auto& l : mSnap.layers)
        if (l.state != "ready") degraded += (degraded.empty() ? "" : ",") + l.id;
    if (mSnap.storeDegraded) degraded += (degraded.empty() ? "" : ",") + std::string("store");
    line += degraded.empty() ? ", all layers ready" : ", degraded: " + degraded;
    if (mSnap.paused) line += ", paused";
    if (!mSnap.holding.empty()) line += ", holding: " + mSnap.holding;
    return line;
}

const std::vector<ControlCommand>& KioskService::takeControl() {
    mControl.drain(mTaken);
    return mTaken;
}

void KioskService::stopping() {
    mNotifier.send("STOPPING=1");
}

}  // namespace kiosk::service
