#include "runtime/app/KioskHooks.h"

#include "config/KioskFile.h"
#include "runtime/app/MemoryBudgets.h"
#include "runtime/app/Report.h"
#include "runtime/app/Session.h"
#include "runtime/app/Signals.h"
#include "runtime/core/ExitCode.h"
#include "runtime/core/Log.h"
#include "runtime/io/StoreReader.h"

#include <sqlite3.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <malloc.h>
#include <thread>

namespace kiosk::app {
namespace {
constexpr const char* kTag = "kiosk";
/** @brief After a playlist switch found nothing playable, wait this long before trying again. */
constexpr double kRetrySeconds = 10.0;
}  // namespace

const std::vector<std::string>& KioskHooks::optionNames() {
    static const std::vector<std::string> names = {"listen", "token-file"};
    return names;
}

std::unique_ptr<KioskHooks> KioskHooks::create(const Args& args, const std::filesystem::path& file,
                                               int& exitCode) {
    service::ServiceOptions opts;
    std::string why;
    std::unique_ptr<KioskPlaylist> playlist;
    if (config::isKioskFile(file)) {
        auto kf = config::readKioskFile(file);
        if (!kf) {
            printDiagnostics(kf.diagnostics);
            exitCode = kExitBadInput;
            return nullptr;
        }
        // Every store connection opened from now on (the playlist's sessions, their loaders).
        io::StoreReader::setPageCacheBytes(kf->memory.sqlitePageCache.bytes);
        playlist = std::make_unique<KioskPlaylist>(std::move(*kf.value));
    }
    std::optional<std::string> listen = args.value("listen");
    if (!listen && playlist) listen = playlist->file().listen;
    if (listen) {
        opts.listen = service::parseListenAddress(*listen, why);
        if (!opts.listen) {
            std::fprintf(stderr, "geokiosk play: %s\n", why.c_str());
            exitCode = kExitUsage;
            return nullptr;
        }
    }
    std::optional<std::filesystem::path> token;
    if (auto t = args.value("token-file")) token = *t;
    if (!token && playlist) token = playlist->file().tokenFile;
    if (token) {
        if (!opts.listen) {
            std::fprintf(stderr,
                         "geokiosk play: --token-file needs --listen (control is served "
                         "over HTTP)\n");
            exitCode = kExitUsage;
            return nullptr;
        }
        opts.tokenFile = *token;
    }
    auto hooks = std::make_unique<KioskHooks>();
    hooks->mPlaylist = std::move(playlist);
    hooks->mFile = file;
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
                r.clock = true;
                break;
            case service::ControlAction::Play:
                clock.resume();
                r.clock = true;
                break;
            case service::ControlAction::Seek:
                clock.seek(c.time);
                r.clock = true;
                break;
            case service::ControlAction::Rate:
                clock.setRate(c.rate);
                r.clock = true;
                break;
            case service::ControlAction::Next:
                r.playlistStep = mPendingStep = 1;
                break;
            case service::ControlAction::Previous:
                r.playlistStep = mPendingStep = -1;
                break;
            case service::ControlAction::Reload:
                r.reload = true;
                break;
            case service::ControlAction::Lens:
                r.lens.push_back(c.lens);
                break;
        }
    }
    return r;
}

void KioskHooks::frameDone(Session& session, const anim::ScenarioClock& clock,
                           const std::filesystem::path& scenario, double frameMs, double dataTime) {
    if (&session != mLastDrawn) {
        // A session was replaced (reload, playlist step, store swap) and the old one is gone.
        // Its heap is freed but glibc keeps the pages (free chunks below the new session's
        // blocks cannot leave the brk heap): measured, RSS stayed ~8 MB higher over 45 reloads
        // with the heap in use the same (geokiosk_heap_in_use_bytes). malloc_trim gives every
        // free page back (madvise), once per swap, off the steady frame path.
        if (mLastDrawn) malloc_trim(0);
        mLastDrawn = &session;
    }
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
    const Session::MemoryUsage memory = session.memoryUsage();
    s.cache.luts = memory.lutBytes;
    s.cache.mappings = memory.mappingBytes;
    s.cache.fontAtlas = memory.fontAtlasBytes;
    const EffectiveBudgets b = effectiveBudgets(session.scenario().memoryBudgets);
    s.budgets.cpuTiles = usage.cpuBudget;
    s.budgets.gpu = usage.gpuBudget;
    s.budgets.luts = b.lutBytes;
    s.budgets.mappings = b.mappingBytes;
    s.budgets.fontAtlas = b.fontAtlasBytes;
    s.budgets.storeConnections = io::StoreReader::openConnections();
    s.budgets.sqlitePageCache = std::uint64_t(io::StoreReader::pageCacheBytes()) *
                                std::uint64_t(s.budgets.storeConnections);
    const auto& layers = session.terrain().layerStatus();
    s.layers.resize(layers.size());
    for (std::size_t i = 0; i < layers.size(); ++i) {
        s.layers[i].id = layers[i].id;
        s.layers[i].state = layers[i].state == scene::LayerState::Ready      ? "ready"
                            : layers[i].state == scene::LayerState::Degraded ? "degraded"
                                                                             : "failed";
        s.layers[i].message = layers[i].message;
    }
    if (s.scenario != scenario.native()) s.scenario = scenario.native();  // no per-frame copy
    // Store swap / deletion: watch the stores of whatever session is on screen (playlist entry,
    // hot reload or swap re-open).
    if (mWatched != &session) {
        mStores.watch(session.scenario());
        mWatched = &session;
        s.storeFiles = mStores.files();
    }
    mAtStepBoundary = fi.shownFrameA != mLastShownFrame || fi.shownFrameA < 0 || clock.paused();
    mLastShownFrame = fi.shownFrameA;
    s.storeDegraded = mStores.degraded();
    s.warnings.clear();
    if (s.storeDegraded) s.warnings.push_back(mStores.degradedWhy());
    if (mPlaylist) {
        s.playlistIndex = mPlaylist->index();
        s.playlistLength = mPlaylist->size();
        s.playlistSkipped = mPlaylist->skipped();
        for (auto& w : mPlaylist->warnings()) s.warnings.push_back(std::move(w));
    }
    s.dataTime = dataTime;
    s.paused = clock.paused();
    mService->frameCompleted(frameMs);
}

Result<std::unique_ptr<Session>> KioskHooks::openFirst(const gl::Caps& caps) {
    if (!mPlaylist) return Session::open(mFile, caps);
    Diagnostics errors;
    auto s = mPlaylist->open(0, caps, errors);
    if (s) return Result<std::unique_ptr<Session>>(std::move(s));
    if (errors.empty())
        errors.error("KIOSK_NOTHING_TO_PLAY", mFile.string(), "/playlist",
                     "no entry can play now (every entry broken or outside its window)");
    return Result<std::unique_ptr<Session>>(std::move(errors));
}

std::unique_ptr<Session> KioskHooks::nextSession(const anim::ScenarioClock& clock,
                                                 const gl::Caps& caps) {
    mKeepTime = false;
    const double now = service::monotonicSeconds();
    mStores.poll(now);
    if (mStores.swapReady() && mAtStepBoundary) {
        // A new model run: the same scenario on the replaced store, from the same data time.
        auto next = reopen(caps);
        noteReload(next.ok());
        mWatched = nullptr;  // watch the new files (also after a failure: no retry loop)
        if (!next) {
            for (const auto& d : next.diagnostics.items())
                KIOSK_LOG_ERROR(kTag, "replaced store refused, keeping the old picture: %s",
                                d.format().c_str());
            return nullptr;
        }
        ++mService->snapshot().storeSwaps;
        mKeepTime = true;
        return std::move(*next.value);
    }
    if (!mPlaylist) return nullptr;
    const int step = mPendingStep != 0 ? mPendingStep : (mPlaylist->finished(clock) ? 1 : 0);
    mPendingStep = 0;
    if (step == 0) return nullptr;
    if (now < mRetryAt) return nullptr;
    Diagnostics errors;
    auto s = mPlaylist->open(step, caps, errors);
    // Nothing else can play: keep the picture and try again in a while, not every frame.
    if (!s) mRetryAt = now + kRetrySeconds;
    return s;
}

Result<std::unique_ptr<Session>> KioskHooks::reopen(const gl::Caps& caps) {
    return mPlaylist ? mPlaylist->reopen(caps) : Session::open(mFile, caps);
}

Result<std::unique_ptr<Session>> KioskHooks::adopt(Result<std::unique_ptr<config::Scenario>> loaded,
                                                   const gl::Caps& caps) {
    if (!loaded) return loaded.diagnostics;
    for (const auto& d : loaded.diagnostics.items()) KIOSK_LOG_WARN(kTag, "%s", d.format().c_str());
    if (mPlaylist) return mPlaylist->create(std::move(*loaded.value), caps);
    return Session::create(std::move(*loaded.value), caps);
}

std::filesystem::path KioskHooks::currentScenario() const {
    return mPlaylist ? mPlaylist->currentScenario() : mFile;
}

float KioskHooks::curtain() const {
    return mPlaylist ? mPlaylist->curtain() : 0.0f;
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
