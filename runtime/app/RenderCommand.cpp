#include "runtime/app/RenderCommand.h"

#include "runtime/anim/BriefingTimeline.h"
#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Args.h"
#include "runtime/app/FrameOutput.h"
#include "runtime/app/FrameStats.h"
#include "runtime/app/Report.h"
#include "runtime/app/Session.h"
#include "runtime/app/StartupPhases.h"
#include "runtime/app/WallScreen.h"
#include "runtime/core/Clock.h"
#include "runtime/core/ExitCode.h"
#include "runtime/core/Log.h"
#include "runtime/core/Progress.h"
#include "runtime/core/Strings.h"
#include "runtime/core/TimeParse.h"
#include "runtime/gl/Context.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/platform/Display.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <thread>

namespace kiosk::app {
namespace {

constexpr const char* kTag = "render";
/** A chapter that pauses in `play` holds its last frame this long in an export. */
constexpr double kPauseHoldSeconds = 2.0;
/** How long one frame may wait for its tiles before it is drawn with what is resident. */
constexpr double kSettleTimeoutSeconds = 120.0;
/** A warm-up draw that found no tile resident is tried again after this long. */
constexpr double kWarmUpRetrySeconds = 0.05;

constexpr const char* kUsage =
    "usage: geokiosk render SCENARIO --out OUT [--time T | "
    "--from T0 --to T1 --fps N] [--size WxH] [--viewpoint NAME] "
    "[--stats STATS.json] [--reference lod|full] [--crf N] [--preset P] [--quiet] "
    "[--occlusion-culling on|off] [--wall WALL.json --screen ID]\n"
    "  OUT: x.png | dir/ | x.mp4 (H.264) | x.mkv (FFV1 lossless) | "
    "x.webm (VP9)\n";

int usage(const std::string& message) {
    std::fprintf(stderr, "geokiosk render: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
}

/**
 * @brief While the loader decodes the first view's tiles the render thread would only wait: a
 * draw of what is resident, scissored to one pixel, makes llvmpipe's shader variants of the
 * stack, the overlays' font atlas and Session::drawFrame's compiler-page release then instead
 * of in the first frame (docs/performance.md §5.2). The frame drawn next clears it: same pixels.
 * @return whether it drew a tile (else it is tried again when more tiles may be resident)
 */
bool drawWarmUp(Session& s, const math::Camera& cam, double time, int width, int height) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 1, 1);
    const FrameRecord r = s.drawFrame(cam, time, width, height);
    glDisable(GL_SCISSOR_TEST);
    return r.tilesDrawn > 0;
}

}  // namespace

int runRenderCommand(const std::vector<std::string>& argv) {
    StartupPhases phases;  // GEOKIOSK_LOG=debug: when each step of the first frame ended
    phases.mark("main");
    Args args("render",
              {"out", "time", "from", "to", "fps", "size", "viewpoint", "stats", "reference", "crf",
               "preset", "wall", "screen", "occlusion-culling"},
              {"quiet"});
    if (!args.parse(argv)) return usage(args.error());
    if (args.help()) return showHelp(kUsage);
    if (args.positionals().size() != 1) return usage("expected exactly one SCENARIO");
    const std::filesystem::path scenarioPath = args.positionals()[0];
    const auto out = args.value("out");
    if (!out || out->empty()) return usage("--out is required");
    const auto outKind = FrameOutput::kindOf(*out);
    if (!outKind)
        return usage("--out must end in .png (one frame), / (a folder), .mp4, .mkv or .webm");
    const bool toDir = *outKind == FrameOutput::Kind::PngFolder;
    const bool toVideo = *outKind == FrameOutput::Kind::Video;
    const bool range = args.value("from") || args.value("to");
    if (range && args.value("time")) return usage("--time and --from/--to are exclusive");
    if (range && (!args.value("from") || !args.value("to")))
        return usage("--from and --to go together");
    if (range && !toDir && !toVideo)
        return usage("--from/--to write many frames: --out must be a folder/ or a video");
    std::optional<int> crf;
    if (auto c = args.value("crf")) {
        const auto format = video::videoFormatForPath(*out);
        if (!format || *format == video::VideoFormat::Ffv1Mkv)
            return usage("--crf applies to .mp4 and .webm (FFV1 .mkv is lossless)");
        char* end = nullptr;
        const long v = std::strtol(c->c_str(), &end, 10);
        if (end == c->c_str() || *end || v < 0 || v > video::maxCrf(*format))
            return usage("--crf wants an integer 0.." + std::to_string(video::maxCrf(*format)) +
                         ", got '" + *c + "'");
        crf = int(v);
    }
    std::string preset;
    if (auto p = args.value("preset")) {
        const auto format = video::videoFormatForPath(*out);
        if (!format || *format != video::VideoFormat::H264Mp4)
            return usage("--preset applies to .mp4 (libx264)");
        if (!video::isX264Preset(*p))
            return usage("--preset wants one of " + video::x264PresetNames() + ", got '" + *p +
                         "'");
        preset = *p;
    }
    int width = 1280, height = 720;
    if (auto size = args.value("size")) {
        auto wh = parseSize(*size);
        if (!wh) return usage("--size wants WIDTHxHEIGHT, got '" + *size + "'");
        width = wh->first;
        height = wh->second;
    }
    // A wall's screen: its size and its off-axis part of the virtual camera (docs/wall.md).
    int wallExit = -1;
    const std::optional<WallScreen> wallScreen = wallScreenFromArgs(args, wallExit);
    if (wallExit >= 0) return wallExit;
    if (wallScreen) {
        if (args.value("size"))
            return usage("with --wall the screen's size comes from the wall file; drop --size");
        width = wallScreen->width();
        height = wallScreen->height();
    }
    if (const auto format = video::videoFormatForPath(*out);
        format && *format != video::VideoFormat::Ffv1Mkv && (width % 2 || height % 2))
        return usage(std::string(video::videoFormatName(*format)) +
                     " is 4:2:0 and needs an even --size, got " + std::to_string(width) + "x" +
                     std::to_string(height));
    // A video plays at --fps, so its default is a smooth one; PNG series keep one per second.
    double fps = toVideo ? 30.0 : 1.0;
    if (auto f = args.value("fps")) {
        char* end = nullptr;
        fps = std::strtod(f->c_str(), &end);
        if (end == f->c_str() || *end || !(fps > 0) || fps > 1000)
            return usage("--fps wants a positive number");
    }
    std::optional<TimeSpec> at, from, to;
    for (auto [name, slot] :
         {std::pair{"time", &at}, std::pair{"from", &from}, std::pair{"to", &to}}) {
        if (auto v = args.value(name)) {
            *slot = parseTimeSpec(*v);
            if (!*slot)
                return usage("--" + std::string(name) +
                             " wants an ISO 8601 UTC time or +offset, got '" + *v + "'");
        }
    }
    const auto reference = args.value("reference");
    if (reference && *reference != "lod" && *reference != "full")
        return usage("--reference wants lod or full, got '" + *reference + "'");
    const auto occlusion = args.value("occlusion-culling");
    if (occlusion && *occlusion != "on" && *occlusion != "off")
        return usage("--occlusion-culling wants on or off, got '" + *occlusion + "'");
    std::error_code ec;
    if (!std::filesystem::exists(scenarioPath, ec)) {
        std::fprintf(stderr, "%s: scenario file not found\n", scenarioPath.c_str());
        return kExitBadInput;
    }

    // The scenario and its stores' metadata are read (no GL, ~15 ms) while the driver starts
    // (~0.2 s; docs/performance.md §5.2). Errors keep their order: a machine that cannot draw
    // says so before a scenario's mistakes.
    auto checked = std::async(std::launch::async, Session::readChecked, scenarioPath);
    platform::DisplayOptions dopts;
    dopts.kind = platform::DisplayKind::Headless;
    dopts.width = width;
    dopts.height = height;
    auto display = platform::createDisplay(dopts);
    if (!display) {
        printDiagnostics(display.diagnostics);
        return kExitCannotRun;
    }
    auto caps = gl::initContext();
    if (!caps) {
        printDiagnostics(caps.diagnostics);
        return kExitCannotRun;
    }
    phases.mark("display");
    auto scenario = checked.get();
    if (!scenario) {
        printDiagnostics(scenario.diagnostics);
        return kExitBadInput;
    }
    Session::sayWarnings(scenario.diagnostics);
    // --reference full: the same view at full resolution, to compare a LOD frame against.
    auto session = Session::create(
        std::move(*scenario.value), *caps, [&reference, &occlusion](config::Scenario& sc) {
            if (reference)
                sc.terrain.reference = *reference == "full" ? config::TerrainReference::Full
                                                            : config::TerrainReference::Lod;
            // off: every selected tile drawn (the baseline of docs/terrain.md §10)
            if (occlusion) sc.terrain.occlusionCulling = *occlusion == "on";
        });
    if (!session) {
        printDiagnostics(session.diagnostics);
        return kExitBadInput;
    }
    phases.mark("session");
    auto target = gl::RenderTarget::create(width, height);
    if (!target) {
        printDiagnostics(target.diagnostics);
        return kExitCannotRun;
    }
    phases.mark("target");
    Session& s = **session;
    if (wallScreen) s.setOverlayLayout(wallScreen->overlayLayout());
    std::vector<double> times;
    std::vector<anim::BriefingFrame> frames;  // briefing export only: each frame's chapter
    std::vector<anim::ChapterFrames> chapterFrames;
    if (range) {
        const double t0 = from->resolve(s.startTime()), t1 = to->resolve(s.startTime());
        if (t1 < t0) return usage("--to is before --from");
        // --fps counts frames per second of *playback*: the scenario clock's rate (data
        // seconds per wall second) sets how much data time each frame advances.
        const double rate = s.scenario().clock && s.scenario().clock->rate != 0
                                ? std::fabs(s.scenario().clock->rate)
                                : 1.0;
        const std::int64_t n = anim::frameCount(t0, t1, fps, rate);
        for (std::int64_t i = 0; i < n; ++i)
            times.push_back(anim::timeForFrame(t0, t1, fps, i, rate));
        // Frames ahead of the playhead load while the current one is waited for and drawn.
        scene::Playback playback;
        playback.rate = rate;  // data seconds per playback second
        playback.start = t0;
        playback.end = t1;
        s.setPlayback(playback);
    } else if (!at && (toDir || toVideo) && s.scenario().briefing) {
        // The briefing: its chapters back to back, each with its camera, layers and caption.
        frames = anim::briefingFrames(s.chapterSpans(), fps, kPauseHoldSeconds, &chapterFrames);
        for (const auto& f : frames) times.push_back(f.time);
    } else {
        times.push_back(at ? at->resolve(s.startTime()) : s.startTime());
    }
    if (toDir) std::filesystem::create_directories(*out, ec);
    std::optional<FrameOutput> output;
    if (toVideo) {
        video::VideoOptions vo;
        vo.path = *out;
        vo.format = *video::videoFormatForPath(*out);
        vo.width = width;
        vo.height = height;
        vo.fps = fps;
        vo.crf = crf;
        vo.preset = preset;
        for (std::size_t c = 0; c < chapterFrames.size(); ++c)
            vo.chapters.push_back({s.scenario().briefing->chapters[c].title,
                                   double(chapterFrames[c].first) / fps,
                                   double(chapterFrames[c].end) / fps});
        auto opened = FrameOutput::video(vo);
        if (!opened) {
            printDiagnostics(opened.diagnostics);
            // No encoder in this FFmpeg build, or no FFmpeg module installed: cannot run here.
            const bool cannot =
                opened.diagnostics.has("EXPORT_CODEC") || opened.diagnostics.has("EXPORT_MODULE");
            return cannot ? kExitCannotRun : kExitBadInput;
        }
        output.emplace(std::move(*opened.value));
    } else {
        output.emplace(toDir ? FrameOutput::folder(*out) : FrameOutput::png(*out));
    }

    // A bar on a terminal, a line per 10 % in logs; one-frame renders need neither.
    Progress progress(args.flag("quiet") || times.size() < 2, "frames");
    progress.begin("render " + std::filesystem::path(*out).filename().string(),
                   std::int64_t(times.size()));
    FrameStats stats(times.size());
    RealClock clock;
    const std::string viewpoint = args.value("viewpoint").value_or("");
    for (std::size_t i = 0; i < times.size(); ++i) {
        if (!frames.empty() && frames[i].chapter != s.chapterIndex()) {
            s.setChapter(frames[i].chapter);
            const anim::ChapterSpan& span = s.chapterSpans()[std::size_t(frames[i].chapter)];
            scene::Playback playback;  // prefetch along this chapter's span
            playback.rate = (span.to - span.from) / span.seconds;
            playback.start = span.from;
            playback.end = span.to;
            s.setPlayback(playback);
        }
        auto vp = s.viewpointAt(times[i], viewpoint);
        if (!vp) {
            printDiagnostics(vp.diagnostics);
            return kExitBadInput;
        }
        const math::Camera cam =
            wallScreen
                ? wallScreen->camera(*vp, s.terrain().bounds(), s.scenario().camera.fovY)
                : makeCamera(*vp, s.terrain().bounds(), width, height, s.scenario().camera.fovY);
        target->bind();
        // Deterministic output: redraw until every tile of this view (and both frames of each
        // sequence pair) is resident, then keep that last, complete frame.
        const double waitStart = clock.now();
        bool warm = i > 0;  // the first frame only: later ones find the variants made
        double lastWarmUp = -1.0;
        for (s.prepare(cam, times[i]); !s.terrain().settled(); s.prepare(cam, times[i])) {
            if (!warm && clock.now() - lastWarmUp > kWarmUpRetrySeconds) {
                lastWarmUp = clock.now();
                warm = drawWarmUp(s, cam, times[i], width, height);
            }
            if (clock.now() - waitStart > kSettleTimeoutSeconds) {
                KIOSK_LOG_WARN(
                    kTag, "frame %zu: tiles still missing after %.0f s; drawing what is resident",
                    i + 1, kSettleTimeoutSeconds);
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        if (i == 0) phases.mark("settled");
        const double t0 = clock.now();
        FrameRecord rec = s.drawFrame(cam, times[i], width, height);
        glFinish();
        rec.frameMs = (clock.now() - t0) * 1000.0;
        stats.add(rec);
        if (i == 0) phases.mark("drawn");
        Diagnostics d;
        if (!output->write(*target, d)) {
            printDiagnostics(d);
            return kExitBadInput;
        }
        if (i == 0) {
            phases.mark("written");
            phases.log(kTag);
            const scene::SceneFrameInfo& f = s.terrain().frameInfo();
            KIOSK_LOG_DEBUG(kTag,
                            "first frame: %u tiles drawn, %u occluded; occlusion: %u rounds, %u "
                            "queries, %.1f ms",
                            f.tilesDrawn, f.tilesOccluded, f.occlusionRounds, f.occlusionQueries,
                            f.occlusionMs);
        }
        progress.advance();
    }
    if (Diagnostics d; !output->finish(d)) {
        printDiagnostics(d);
        return kExitBadInput;
    }
    progress.finish();
    if (auto statsPath = args.value("stats")) {
        stats.setBudgets(s.budgets());
        Diagnostics d;
        if (!stats.write(*statsPath, d)) {
            printDiagnostics(d);
            return kExitBadInput;
        }
    }
    if (!args.flag("quiet"))
        std::fprintf(stderr, "render: wrote %zu frame%s to %s\n", times.size(),
                     times.size() == 1 ? "" : "s", out->c_str());
    for (const auto& st : s.terrain().layerStatus())
        if (st.state != scene::LayerState::Ready)
            std::fprintf(stderr, "render: layer %s %s: %s\n", st.id.c_str(),
                         scene::layerStateName(st.state), st.message.c_str());
    return kExitOk;
}

}  // namespace kiosk::app
