#include "runtime/app/PlayCommand.h"

#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Args.h"
#include "runtime/app/FrameStats.h"
#include "runtime/app/Report.h"
#include "runtime/app/Session.h"
#include "runtime/app/Signals.h"
#include "runtime/core/Clock.h"
#include "runtime/core/ExitCode.h"
#include "runtime/core/Log.h"
#include "runtime/core/Strings.h"
#include "runtime/gl/Context.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/platform/Display.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

namespace kiosk::app {
namespace {

constexpr const char* kTag = "play";
/** Scenario files are polled this often; a valid edit shows within a second. */
constexpr double kReloadPollSeconds = 0.5;
/** How far ahead (wall seconds) the camera path is sampled for prefetching. */
constexpr double kPrefetchSeconds = 2.0;
/** `--stats` without `--frames` keeps the newest this many frames (5 min at 60 fps, ~2 MB). */
constexpr std::size_t kStatsWindow = 18000;

int usage(const std::string& message) {
    std::fprintf(stderr,
                 "geokiosk play: %s\nusage: geokiosk play SCENARIO [--display "
                 "auto|kms|x11|wayland|headless] [--size WxH] [--windowed] [--max-fps N] "
                 "[--frames N] [--connector NAME] [--drm-device PATH] [--stats STATS.json]\n",
                 message.c_str());
    return kExitUsage;
}

/** Modification stamps of the scenario and everything it includes (into `out`, reused: the
 * poll runs in the frame loop, which must not allocate once running). */
void stamps(const std::vector<std::filesystem::path>& files,
            std::vector<std::filesystem::file_time_type>& out) {
    out.resize(files.size());
    for (std::size_t i = 0; i < files.size(); ++i) {
        std::error_code ec;
        out[i] = std::filesystem::last_write_time(files[i], ec);
    }
}

anim::ScenarioClock makeClock(const Session& s) {
    auto clock = anim::ScenarioClock::create(s.clockSettings());
    return clock ? *clock.value : anim::ScenarioClock();
}

}  // namespace

int runPlayCommand(const std::vector<std::string>& argv) {
    Args args("play", {"display", "size", "max-fps", "frames", "connector", "drm-device", "stats"},
              {"windowed"});
    if (!args.parse(argv)) return usage(args.error());
    if (args.positionals().size() != 1) return usage("expected exactly one SCENARIO");
    const std::filesystem::path scenarioPath = args.positionals()[0];
    platform::DisplayOptions dopts;
    if (auto d = args.value("display")) {
        auto kind = platform::parseDisplayKind(*d);
        if (!kind) {
            std::string msg = "--display wants auto|kms|x11|wayland|headless, got '" + *d + "'";
            if (auto m = closestMatch(*d, {"auto", "kms", "x11", "wayland", "headless"}))
                msg += " (did you mean '" + *m + "'?)";
            return usage(msg);
        }
        dopts.kind = *kind;
    }
    if (auto size = args.value("size")) {
        auto wh = parseSize(*size);
        if (!wh) return usage("--size wants WIDTHxHEIGHT, got '" + *size + "'");
        dopts.width = wh->first;
        dopts.height = wh->second;
    }
    dopts.windowed = args.flag("windowed");
    dopts.connector = args.value("connector").value_or("");
    dopts.drmDevice = args.value("drm-device").value_or("");
    double maxFps = 0;
    if (auto f = args.value("max-fps")) {
        char* end = nullptr;
        maxFps = std::strtod(f->c_str(), &end);
        // 0 = unthrottled (as fast as the display presents).
        if (end == f->c_str() || *end || !(maxFps >= 0) || !std::isfinite(maxFps))
            return usage("--max-fps wants a number >= 0 (0: unthrottled)");
    }
    long frameLimit = -1;
    if (auto f = args.value("frames")) {
        char* end = nullptr;
        frameLimit = std::strtol(f->c_str(), &end, 10);
        if (end == f->c_str() || *end || frameLimit <= 0) return usage("--frames wants a positive integer");
    }
    std::error_code ec;
    if (!std::filesystem::exists(scenarioPath, ec)) {
        std::fprintf(stderr, "%s: scenario file not found\n", scenarioPath.c_str());
        return kExitBadInput;
    }

    auto display = platform::createDisplay(dopts);
    if (!display) {
        printDiagnostics(display.diagnostics);
        return kExitCannotRun;
    }
    platform::Display& dpy = **display;
    auto caps = gl::initContext();
    if (!caps) {
        printDiagnostics(caps.diagnostics);
        return kExitCannotRun;
    }
    KIOSK_LOG_INFO(kTag, "%s, %s", dpy.describe().c_str(), caps->renderer.c_str());
    auto opened = Session::open(scenarioPath, *caps);
    if (!opened) {
        printDiagnostics(opened.diagnostics);
        return kExitBadInput;
    }
    std::unique_ptr<Session> session = std::move(*opened.value);
    std::optional<gl::RenderTarget> offscreen;
    if (!dpy.hasSurface()) {
        auto rt = gl::RenderTarget::create(dpy.width(), dpy.height());
        if (!rt) {
            printDiagnostics(rt.diagnostics);
            return kExitCannotRun;
        }
        offscreen.emplace(std::move(*rt.value));
    }

    const auto statsPath = args.value("stats");
    FrameStats stats(frameLimit > 0 ? std::size_t(frameLimit) : 0);
    if (frameLimit <= 0) stats.keepNewest(kStatsWindow);
    // Written on every way out of the loop once frames were drawn (stop, --frames, errors).
    const auto writeStats = [&] {
        if (!statsPath) return true;
        stats.setBudgets(session->budgets());
        Diagnostics d;
        if (stats.write(*statsPath, d)) return true;
        printDiagnostics(d);
        return false;
    };

    installStopSignals();
    RealClock wall;
    anim::ScenarioClock clock = makeClock(*session);
    auto watched = session->scenario().sourceFiles;
    std::vector<std::filesystem::file_time_type> watchedStamps, current;
    stamps(watched, watchedStamps);
    double lastPoll = wall.now(), last = wall.now();
    platform::InputState input;
    std::optional<math::Viewpoint> manual;  // set while the user steers the camera
    for (long frame = 0; frameLimit < 0 || frame < frameLimit; ++frame) {
        if (stopRequested()) break;
        dpy.pollInput(input);
        if (input.quitRequested) break;
        const double now = wall.now();
        const double dt = now - last;
        last = now;

        if (now - lastPoll >= kReloadPollSeconds) {
            lastPoll = now;
            stamps(watched, current);
            if (current != watchedStamps) {
                watchedStamps = current;
                auto next = Session::open(scenarioPath, *caps);
                if (next) {
                    session = std::move(*next.value);
                    clock = makeClock(*session);
                    watched = session->scenario().sourceFiles;
                    stamps(watched, watchedStamps);
                    KIOSK_LOG_INFO(kTag, "%s: reloaded", scenarioPath.c_str());
                } else {
                    // Keep the last good scenario on screen; say exactly why the edit was refused.
                    for (const auto& d : next.diagnostics.items())
                        KIOSK_LOG_ERROR(kTag, "edit rejected, keeping the previous scenario: %s",
                                        d.format().c_str());
                    if (const Diagnostic* e = next.diagnostics.firstError())
                        session->setNotice("scenario edit rejected: " + e->format());
                }
            }
        }

        if (input.togglePause) clock.paused() ? clock.resume() : clock.pause();
        if (input.step != 0) {
            const auto keys = session->terrain().sequenceKeyTimes();
            input.step > 0 ? clock.stepToNextKey(keys) : clock.stepToPreviousKey(keys);
        }
        const bool ready = !session->terrain().frameInfo().holdingSequence;
        const double t = clock.advance(dt, ready).time;
        auto vp = session->viewpointAt(t, "");
        // Interactive control (when the scenario allows it): the first navigation key takes the
        // camera off its path from where it is; h / Home gives it back.
        if (session->scenario().camera.interactive) {
            if (input.home) manual.reset();
            if ((input.orbit || input.tilt || input.zoom) && !manual && vp) manual = *vp;
            if (manual) {
                manual->headingDeg += 10.0 * input.orbit;
                manual->pitchDeg = std::clamp(manual->pitchDeg + 5.0 * input.tilt, -89.0, -5.0);
                manual->range *= std::pow(0.8, input.zoom);
                vp = *manual;
            }
        }
        input.clearRequests();
        const int w = dpy.width(), h = dpy.height();
        const math::Camera cam = vp ? makeCamera(*vp, session->terrain().bounds(), w, h,
                                                 session->scenario().camera.fovY)
                                    : makeCamera(session->terrain().overviewViewpoint(),
                                                 session->terrain().bounds(), w, h, 45.0);
        if (offscreen)
            offscreen->bind();
        else
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        session->setPlayback(scene::playbackOf(clock));
        const double drawStart = wall.now();
        FrameRecord rec = session->drawFrame(cam, t, w, h);
        // Camera paths are known in advance: ask for the tiles of the view two seconds ahead.
        if (auto ahead = session->viewpointAt(clock.predict(kPrefetchSeconds), ""))
            session->terrain().prefetch(makeCamera(*ahead, session->terrain().bounds(), w, h,
                                                   session->scenario().camera.fovY));
        if (!dpy.swapBuffers()) {
            KIOSK_LOG_ERROR(kTag, "presenting the frame failed; stopping");
            writeStats();
            return kExitCannotRun;
        }
        if (offscreen) glFinish();
        // Frame time as in `render`: drawing until the frame is done (here presented).
        rec.frameMs = (wall.now() - drawStart) * 1000.0;
        stats.add(rec);
        if (maxFps > 0) {
            const double spent = wall.now() - now;
            const double wait = 1.0 / maxFps - spent;
            if (wait > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
        }
    }
    if (!writeStats()) return kExitBadInput;
    KIOSK_LOG_INFO(kTag, "stopped cleanly");
    return kExitOk;
}

}  // namespace kiosk::app
