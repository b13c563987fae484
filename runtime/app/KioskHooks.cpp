#include "runtime/app/KioskHooks.h"

#include "runtime/app/Session.h"
#include "runtime/app/Signals.h"
#include "runtime/core/ExitCode.h"
#include "runtime/core/Log.h"

#include <sqlite3.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

namespace kiosk::app {
namespace {
constexpr const char* kTag = "kiosk";
}

const std::vector<std::string>& KioskHooks::optionNames() {
    static const std::vector<std::string> names = {"listen", "token-file"};
    return names;
}

std::unique_ptr<KioskHooks> KioskHooks::create(const Args& args, int& exitCode) {
    service::ServiceOptions opts;
    std::string why;
    if (auto l = args.value("listen")) {
        opts.listen = service::parseListenAddress(*l, why);
        if (!opts.listen) {
            std::fprintf(stderr, "geokiosk play: %s\n", why.c_str());
            exitCode = kExitUsage;
            return nullptr;
        }
    }
    if (auto t = args.value("token-file")) {
        if (!opts.listen) {
            std::fprintf(stderr,
                         "geokiosk play: --token-file needs --listen (control is served "
                         "over HTTP)\n");
            exitCode = kExitUsage;
            return nullptr;
        }
        opts.tokenFile = *t;
    }
    auto hooks = std::make_unique<KioskHooks>();
    hooks->mService = service::KioskService::start(opts, why);
    if (!hooks->mService) {
        std::fprintf(stderr, "geokiosk play: %s\n", why.c_str());
        // An unreadable token file is bad input; a port that cannot be bound is this machine.
        exitCode = why.find("token") != std::string::npos ? kExitBadInput : kExitCannotRun;
        return nullptr;
    }
    if (const char* stall = std::getenv("GEOKIOSK_TEST_STALL_FILE")) hooks->mStallFile = stall;
    return hooks;
}

KioskHooks::Requests KioskHooks::applyControl(anim::ScenarioClock& clock) {
    Requests r;
    for (const auto& c : mService->takeControl()) {
        KIOSK_LOG_INFO(kTag, "control: %s", service::controlActionName(c.action));
        switch (c.action) {
            case service::ControlAction::Pause:
                clock.pause();
                break;
            case service::ControlAction::Play:
                clock.resume();
                break;
            case service::ControlAction::Seek:
                clock.seek(c.time);
                break;
            case service::ControlAction::Rate:
                clock.setRate(c.rate);
                break;
            case service::ControlAction::Next:
                r.playlistStep = 1;
                break;
            case service::ControlAction::Previous:
                r.playlistStep = -1;
                break;
            case service::ControlAction::Reload:
                r.reload = true;
                break;
        }
    }
    return r;
}

void KioskHooks::frameDone(Session& session, const anim::ScenarioClock& clock,
                           const std::filesystem::path& scenario, double frameMs, double dataTime) {
    service::ServiceSnapshot& s = mService->snapshot();
    const scene::SceneFrameInfo& fi = session.terrain().frameInfo();
    if (fi.holdingSequence) ++s.heldFrames;
    if (fi.sequenceTilesMissing > 0) ++s.sequenceMissingFrames;
    const scene::SceneCacheUsage usage = session.terrain().cacheUsage();
    s.cache.cpuTiles = usage.cpuTiles;
    s.cache.gpuTextures = usage.gpuTextures;
    s.cache.gpuMeshes = usage.gpuMeshes;
    sqlite3_int64 current = 0, high = 0;
    // Page cache memory SQLite took from the heap (no static page cache is configured).
    if (sqlite3_status64(SQLITE_STATUS_PAGECACHE_OVERFLOW, &current, &high, 0) == SQLITE_OK)
        s.cache.sqlitePageCache = std::uint64_t(current);
    s.loaderQueue = usage.loaderQueue;
    const auto& layers = session.terrain().layerStatus();
    s.layers.resize(layers.size());
    for (std::size_t i = 0; i < layers.size(); ++i) {
        s.layers[i].id = layers[i].id;
        s.layers[i].state = layers[i].state == scene::LayerState::Ready      ? "ready"
                            : layers[i].state == scene::LayerState::Degraded ? "degraded"
                                                                             : "failed";
        s.layers[i].message = layers[i].message;
    }
    s.scenario = scenario.string();
    s.dataTime = dataTime;
    s.paused = clock.paused();
    mService->frameCompleted(frameMs);
}

void KioskHooks::noteReload(bool ok) {
    ++(ok ? mService->snapshot().reloads : mService->snapshot().reloadFailures);
}

void KioskHooks::stallWhileTestFileExists() {
    if (mStallFile.empty()) return;
    std::error_code ec;
    while (std::filesystem::exists(mStallFile, ec) && !stopRequested())
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

}  // namespace kiosk::app
