#include "runtime/app/PlayCommand.h"

#include "runtime/anim/BriefingPlayer.h"
#include "runtime/anim/FrameGovernor.h"
#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Args.h"
#include "runtime/app/BriefingControl.h"
#include "runtime/app/KioskHooks.h"
#include "runtime/app/LensControl.h"
#include "runtime/app/Report.h"
#include "runtime/app/ScenarioReloader.h"
#include "runtime/app/Session.h"
#include "runtime/app/Signals.h"
#include "runtime/app/WallNode.h"
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
#include <cstdlib>
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

/**
 * Test hook: GEOKIOSK_TEST_FRAME_COST_MS=MS[:FRAMES] adds an artificial cost to each of the
 * first FRAMES frames (all when omitted), modelled on a fill-bound frame: MS at the scenario's
 * settings, times the rendered fraction of the pixels and the scenario's tauGeom over the one
 * used. Lets the governor be tested on any machine (tests/scenario/GovernorPlayTest).
 */
class TestFrameCost {
public:
    TestFrameCost() {
        const char* v = std::getenv("GEOKIOSK_TEST_FRAME_COST_MS");
        if (!v || !*v) return;
        char* end = nullptr;
        mMs = std::strtod(v, &end);
        if (end && *end == ':') mFrames = std::strtol(end + 1, nullptr, 10);
        if (!(mMs > 0)) mMs = 0;
    }
    void spend(long frame, Session& s) const {
        if (mMs <= 0 || (mFrames >= 0 && frame >= mFrames)) return;
        const double scale = s.renderScale();
        const double tau = s.scenario().terrain.tauGeom / std::max(1e-9, s.terrain().tauGeom());
        const double ms = mMs * scale * scale * tau;
        std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(ms));
    }

private:
    double mMs = 0;
    long mFrames = -1;
};

constexpr const char* kUsage =
    "usage: geokiosk play SCENARIO [--display "
    "auto|kms|x11|wayland|headless] [--size WxH] [--windowed] [--max-fps N] "
    "[--frames N] [--connector NAME] [--drm-device PATH] [--listen HOST:PORT] "
    "[--token-file FILE] [--target-fps N] [--stats STATS.json] "
    "[--wall WALL.json --screen ID [--wall-log LOG.jsonl]]\n";

int usage(const std::string& message) {
    std::fprintf(stderr, "geokiosk play: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
}

/** `--stats` without `--frames` keeps the newest this many frames (5 min at 60 fps, ~2 MB). */
constexpr std::size_t kStatsWindow = 18000;

/** A briefing plays its chapters instead of the clock (and starts on its first chapter). */
std::optional<anim::BriefingPlayer> makeBriefing(Session& s) {
    if (!s.scenario().briefing) return std::nullopt;
    s.setChapter(0);
    return anim::BriefingPlayer(s.chapterSpans());
}

anim::ScenarioClock makeClock(const Session& s) {
    auto clock = anim::ScenarioClock::create(s.clockSettings());
    return clock ? *clock.value : anim::ScenarioClock();
}

/** The scenario's governor, `--target-fps` overriding its frame rate. */
anim::FrameGovernor makeGovernor(const Session& s, std::optional<double> targetFps) {
    const config::Governor& g = s.scenario().governor;
    anim::GovernorSettings gs;
    gs.targetFps = targetFps.value_or(g.targetFps);
    gs.maxTauFactor = g.maxTauFactor;
    gs.minRenderScale = g.minRenderScale;
    return anim::FrameGovernor(gs, s.scenario().terrain.tauGeom, s.scenario().terrain.tauTex);
}

}  // namespace

int runPlayCommand(const std::vector<std::string>& argv) {
    std::vector<std::string> valueOptions = {"display",   "size",       "max-fps",    "frames",
                                             "connector", "drm-device", "target-fps", "stats"};
    for (const auto& o : KioskHooks::optionNames()) valueOptions.push_back(o);
    for (const char* o : {"wall", "screen", "wall-log"})
        valueOptions.push_back(o);  // display walls
    Args args("play", valueOptions, {"windowed"});
    if (!args.parse(argv)) return usage(args.error());
    if (args.help()) return showHelp(kUsage);
    if (args.positionals().size() != 1) return usage("expected exactly one SCENARIO");
    std::filesystem::path scenarioPath = args.positionals()[0];
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
    int wallExit = -1;
    std::optional<WallScreen> wallScreen = wallScreenFromArgs(args, wallExit);
    if (wallExit >= 0) return wallExit;
    if (!wallScreen && args.value("wall-log")) return usage("--wall-log needs --wall");
    if (wallScreen) {
        if (args.value("size"))
            return usage("with --wall the screen's size comes from the wall file; drop --size");
        dopts.width = wallScreen->width();
        dopts.height = wallScreen->height();
    }
    dopts.windowed = args.flag("windowed");
    dopts.shouldStop = stopRequested;
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
    std::optional<double> targetFps;
    if (auto f = args.value("target-fps")) {
        char* end = nullptr;
        targetFps = std::strtod(f->c_str(), &end);
        if (end == f->c_str() || *end || !(*targetFps >= 0) || *targetFps > 240)
            return usage("--target-fps wants a number of frames per second in 0..240 (0: off)");
    }
    long frameLimit = -1;
    if (auto f = args.value("frames")) {
        char* end = nullptr;
        frameLimit = std::strtol(f->c_str(), &end, 10);
        if (end == f->c_str() || *end || frameLimit <= 0)
            return usage("--frames wants a positive integer");
    }
    std::error_code ec;
    if (!std::filesystem::exists(scenarioPath, ec)) {
        std::fprintf(stderr, "%s: scenario file not found\n", scenarioPath.c_str());
        return kExitBadInput;
    }

    // A kiosk file (playlist) or a scenario; systemd notify and the HTTP service.
    int kioskExit = kExitOk;
    auto kiosk = KioskHooks::create(args, scenarioPath, kioskExit);
    if (!kiosk) return kioskExit;
    // From here SIGTERM means "stop cleanly" (exit 0), also during a slow display or store open.
    installStopSignals();

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
    auto opened = kiosk->openFirst(*caps);
    if (!opened) {
        printDiagnostics(opened.diagnostics);
        return kExitBadInput;
    }
    std::unique_ptr<Session> session = std::move(*opened.value);
    scenarioPath = kiosk->currentScenario();
    std::optional<gl::RenderTarget> offscreen;
    if (!dpy.hasSurface()) {
        auto rt = gl::RenderTarget::create(dpy.width(), dpy.height());
        if (!rt) {
            printDiagnostics(rt.diagnostics);
            return kExitCannotRun;
        }
        offscreen.emplace(std::move(*rt.value));
    }

    std::unique_ptr<WallNode> wallNode;
    if (wallScreen) {
        auto node = WallNode::create(std::move(*wallScreen), args.value("wall-log").value_or(""));
        if (!node) {
            printDiagnostics(node.diagnostics);
            return kExitCannotRun;
        }
        wallNode = std::move(*node.value);
    }
    RealClock wall;
    anim::ScenarioClock clock = makeClock(*session);
    std::optional<anim::BriefingPlayer> briefing = makeBriefing(*session);
    anim::FrameGovernor governor = makeGovernor(*session, targetFps);
    TestFrameCost testCost;
    std::optional<FrameStats> stats;
    if (args.value("stats")) {
        // Preallocated: recording never allocates in the frame loop. Without --frames only the
        // newest kStatsWindow frames are kept (a kiosk plays for weeks).
        stats.emplace(frameLimit > 0 ? std::size_t(frameLimit) : 0);
        if (frameLimit <= 0) stats->keepNewest(kStatsWindow);
    }
    // Edits are polled, read and checked on the reloader's worker (which also keeps the stat
    // calls out of this loop); the loop only swaps in a finished, valid scenario and builds its
    // GL half, so a slow or hostile edit never stops the frames.
    ScenarioReloader reloader(scenarioPath, session->scenario().sourceFiles, kReloadPollSeconds);
    KIOSK_LOG_INFO(kTag, "%s: playing, watching %zu files for edits", scenarioPath.c_str(),
                   session->scenario().sourceFiles.size());
    double last = wall.now();
    platform::InputState input;
    std::optional<math::Viewpoint> manual;  // set while the user steers the camera
    for (long frame = 0; frameLimit < 0 || frame < frameLimit; ++frame) {
        if (stopRequested()) break;
        dpy.pollInput(input);
        if (input.quitRequested) break;
        kiosk->stallWhileTestFileExists();
        // Remote control (pause/play/seek/rate act on the clock; reload: the worker re-reads).
        const KioskHooks::Requests control = kiosk->applyControl(clock);
        if (control.reload) reloader.requestLoad();
        for (const auto& move : control.lens)  // POST /control/lens (docs/kiosk.md)
            if (std::string why; !applyLensMove(session->terrain(), move, why))
                KIOSK_LOG_WARN(kTag, "control: lens: %s", why.c_str());
        // A remote pause/play/seek/rate means the operator drives the clock: the briefing's
        // chapters would otherwise keep choosing the time and the command would have no effect.
        if (control.clock) briefing.reset();
        // Playlists: the next entry when this one is done (or next/previous was asked for);
        // a store replaced on disk: the same scenario re-opened on it at a step boundary.
        if (auto next = kiosk->nextSession(clock, *caps)) {
            session = std::move(next);
            const double was = clock.current();
            clock = makeClock(*session);
            briefing = makeBriefing(*session);
            governor = makeGovernor(*session, targetFps);
            if (kiosk->keepsDataTime()) clock.seek(was);
            scenarioPath = kiosk->currentScenario();
            reloader.watch(scenarioPath, session->scenario().sourceFiles);
            manual.reset();
        }
        session->setCurtain(kiosk->curtain());
        const double now = wall.now();
        const double dt = now - last;
        last = now;

        if (auto loaded = reloader.take()) {
            auto next = kiosk->adopt(std::move(*loaded), *caps);  // with the kiosk's budgets
            if (next) {
                session = std::move(*next.value);
                clock = makeClock(*session);
                briefing = makeBriefing(*session);
                governor = makeGovernor(*session, targetFps);
                KIOSK_LOG_INFO(kTag, "%s: reloaded", scenarioPath.c_str());
                kiosk->noteReload(true);
            } else {
                // Keep the last good scenario on screen; say exactly why the edit was refused.
                for (const auto& d : next.diagnostics.items())
                    KIOSK_LOG_ERROR(kTag, "edit rejected, keeping the previous scenario: %s",
                                    d.format().c_str());
                kiosk->noteReload(false);
                if (const Diagnostic* e = next.diagnostics.firstError())
                    session->setNotice("scenario edit rejected: " + e->format());
            }
        }

        const int chapterSteps = takeChapterSteps();  // the control endpoint's next/previous
        if (briefing) {
            // In a briefing space resumes from a chapter's pause, . and , go to the next and
            // previous chapter.
            if (input.togglePause) briefing->togglePause();
            for (int k = input.step + chapterSteps; k != 0; k += k > 0 ? -1 : 1)
                k > 0 ? briefing->next() : briefing->previous();
        } else {
            if (input.togglePause) clock.paused() ? clock.resume() : clock.pause();
            if (input.step != 0) {
                const auto keys = session->terrain().sequenceKeyTimes();
                input.step > 0 ? clock.stepToNextKey(keys) : clock.stepToPreviousKey(keys);
            }
        }
        // On a wall the clock waits for the step to be resident on every node, not just here.
        const bool ready =
            wallNode ? wallNode->stepResident() : !session->terrain().frameInfo().holdingSequence;
        double t = briefing ? briefing->advance(dt, ready) : clock.advance(dt, ready).time;
        // A wall's followers show the leader's chapter (below), not their own briefing's.
        if (briefing && briefing->chapter() != session->chapterIndex() &&
            (!wallNode || wallNode->isLeader()))
            session->setChapter(briefing->chapter());
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
        applyLensKeys(session->terrain(), input);
        input.clearRequests();
        // What the clock plays (a briefing: its chapter's span): sizes the sequences' prefetch.
        scene::Playback playback = scene::playbackOf(clock);
        if (briefing) {
            const anim::ChapterSpan& span =
                session->chapterSpans()[std::size_t(briefing->chapter())];
            playback = {};
            playback.rate = briefing->atPause() || briefing->userPaused()
                                ? 0.0
                                : (span.to - span.from) / span.seconds;
            playback.start = span.from;
            playback.end = span.to;
        }
        if (wallNode) {  // followers draw the leader's frame; nothing new: not a frame
            if (!wallNode->beginFrame(*session, t,
                                      vp ? *vp : session->terrain().overviewViewpoint(), playback,
                                      0.1)) {
                if (wallNode->stopped()) break;
                kiosk->service().holding("no frame state from the wall leader");
                --frame;
                continue;
            }
            t = wallNode->dataTime();
            vp = wallNode->viewpoint();
            // The leader's briefing chapter: its layer overrides and caption on every screen.
            if (!wallNode->isLeader() && wallNode->chapter() != session->chapterIndex())
                session->setChapter(wallNode->chapter());
            session->setOverlayLayout(wallNode->screen().overlayLayout());
            session->terrain().setStepGate(wallNode->stepTime());
        }
        const int w = dpy.width(), h = dpy.height();
        math::Camera cam =
            vp ? makeCamera(*vp, session->terrain().bounds(), w, h, session->scenario().camera.fovY)
               : makeCamera(session->terrain().overviewViewpoint(), session->terrain().bounds(), w,
                            h, 45.0);
        if (wallNode && vp)
            cam = wallNode->screen().camera(*vp, session->terrain().bounds(),
                                            session->scenario().camera.fovY);
        if (offscreen)
            offscreen->bind();
        else
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        session->setPlayback(wallNode ? wallNode->playback() : playback);
        if (!wallNode && governor.state().active) {  // walls: every screen at the same LOD
            session->terrain().setTau(governor.state().tauGeom, governor.state().tauTex);
            session->setRenderScale(governor.state().renderScale);
        }
        FrameRecord rec = session->drawFrame(cam, t, w, h);
        // Camera paths are known in advance: ask for the tiles of the view two seconds ahead.
        if (wallNode) {  // from the leader's playback state, through this screen's frustum
            const scene::Playback p = wallNode->playback();
            const double aheadTime = t + (p.paused ? 0.0 : p.rate * kPrefetchSeconds);
            if (auto ahead = session->viewpointAt(aheadTime, ""))
                session->terrain().prefetch(wallNode->screen().camera(
                    *ahead, session->terrain().bounds(), session->scenario().camera.fovY));
        } else if (auto ahead =
                       session->viewpointAt(briefing ? briefing->timeAhead(kPrefetchSeconds)
                                                     : clock.predict(kPrefetchSeconds),
                                            ""))
            session->terrain().prefetch(makeCamera(*ahead, session->terrain().bounds(), w, h,
                                                   session->scenario().camera.fovY));
        // Swap barrier: every node swaps this frame together (or the leader's deadline passes).
        if (wallNode && !wallNode->barrier(*session, [&] { session->drawFrame(cam, t, w, h); })) {
            --frame;  // the leader moved on or went silent: keep the last frame on screen
            continue;
        }
        // The leader's first frame waits up to 10 s for the followers to join: that wait is
        // start-up, not playback, so the next frame's dt starts after it (no data-time jump).
        if (wallNode && wallNode->isLeader() && frame == 0) last = wall.now();
        if (!dpy.swapBuffers()) {
            KIOSK_LOG_ERROR(kTag, "presenting the frame failed; stopping");
            return kExitCannotRun;
        }
        if (offscreen) glFinish();
        if (wallNode) wallNode->swapped(session->terrain().frameInfo());
        testCost.spend(frame, *session);
        // The frame's cost as the viewer sees it (update, draw, present), not the --max-fps wait.
        rec.frameMs = (wall.now() - now) * 1000.0;
        governor.frameDone(rec.frameMs);
        if (stats) stats->add(rec);
        kiosk->frameDone(*session, clock, scenarioPath, rec.frameMs, t);
        if (maxFps > 0) {
            const double spent = wall.now() - now;
            const double wait = 1.0 / maxFps - spent;
            if (wait > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
        }
    }
    if (wallNode) wallNode->stop();
    kiosk->service().stopping();
    if (stats) {
        stats->setBudgets(session->budgets());
        Diagnostics d;
        if (!stats->write(*args.value("stats"), d)) {
            printDiagnostics(d);
            return kExitBadInput;
        }
    }
    KIOSK_LOG_INFO(kTag, "stopped cleanly");
    return kExitOk;
}

}  // namespace kiosk::app
