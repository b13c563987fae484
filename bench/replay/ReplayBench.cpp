// Replay benchmark (issue 6): plays time sequences through the scene as `geokiosk play` does
// (scenario clock on real wall time, wait-for-data, prefetch ahead of the playhead) headless on
// llvmpipe and prints ONE JSON object. Per scenario and size: fps, frame time p50/p95/p99 and
// whether p99 <= 1.5 x median, frames with missing sequence tiles, held frames, prefetch hits,
// frame steps shown, and the baseline measured in the same run: the llvmpipe fill bound (a
// full-screen quad with the same texture fetches per pixel). Peak RSS for the whole run.
//
// usage: bench-replay [SCENARIO ...] [--sizes 1280x720,1920x1080] [--seconds S]
//                     [--anuga FILE.sww] [--rate R]
//   Without SCENARIO: scenarios/demo/rainier.json. --anuga imports the SWW's bed and depth
//   into a temporary store and replays it at --rate (default 10) as well.
#include "runtime/anim/ScenarioClock.h"
#include "bench/common/PhaseTimes.h"
#include "bench/common/HeadlessGl.h"
#include "runtime/app/FrameStats.h"
#include "runtime/app/Session.h"
#include "runtime/core/Clock.h"
#include "runtime/core/Strings.h"
#include "runtime/core/TimeParse.h"
#include "runtime/gl/Context.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/import/Importer.h"
#include "runtime/platform/Display.h"
#include "runtime/render/FillBound.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

using namespace kiosk;
namespace fs = std::filesystem;

namespace {

double peakRssMb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

anim::ScenarioClock makeClock(const app::Session& s, double rateOverride) {
    anim::ClockSettings cs = s.clockSettings();
    cs.startPaused = false;  // a benchmark always plays
    if (rateOverride > 0) cs.rate = rateOverride;
    auto clock = anim::ScenarioClock::create(cs);
    return clock ? *clock.value : anim::ScenarioClock();
}

/** Import an ANUGA SWW (bed + depth) and write a replay scenario next to it. */
std::string prepareAnuga(const std::string& sww, const fs::path& dir, std::string& error) {
    fs::create_directories(dir);
    import::ImportOptions o;
    o.store = dir / "anuga.gpkg";
    o.quiet = true;
    std::error_code ec;
    fs::remove(o.store, ec);
    o.name = "elevation";
    Diagnostics d = import::importElevation(sww, o);
    o.name = "flood";
    o.start = *parseIso8601("2026-03-14T00:00:00Z");
    if (!d.hasErrors()) d.append(import::importSequence({sww}, o));
    if (d.hasErrors()) {
        error = d.format();
        return {};
    }
    const fs::path scenario = dir / "anuga.json";
    std::ofstream(scenario) << R"({ "version": 1, "title": "ANUGA replay",
        "stores": { "s": "anuga.gpkg" }, "terrain": { "store": "s" },
        "transferFunctions": { "depth": { "units": "m", "stops": [
            { "value": 0, "color": "#c6dbef00" }, { "value": 0.05, "color": "#6baed6" },
            { "value": 2, "color": "#08306b" } ] } },
        "layers": [ { "id": "flood", "kind": "sequence",
                      "source": { "store": "s", "sequence": "flood" },
                      "transfer": "depth", "nodataAs": 0 } ],
        "overlays": { "timeLabel": { "enabled": true } } })";
    return scenario.string();
}

nlohmann::json replay(const std::string& scenario, int w, int h, double seconds, double rate,
                      const gl::Caps& caps) {
    nlohmann::json r;
    r["scenario"] = scenario;
    r["size"] = std::to_string(w) + "x" + std::to_string(h);
    auto target = gl::RenderTarget::create(w, h);
    auto opened = app::Session::open(scenario, caps);
    if (!target || !opened) {
        r["error"] = opened ? target.diagnostics.format() : opened.diagnostics.format();
        return r;
    }
    app::Session& s = **opened;
    target->bind();
    anim::ScenarioClock clock = makeClock(s, rate);
    r["rate"] = clock.rate();
    RealClock wall;
    // Warm-up: the first view resident, as a kiosk is after start-up (not timed).
    auto cameraAt = [&](double t) {
        auto vp = s.viewpointAt(t, "");
        return app::makeCamera(vp ? *vp : s.terrain().overviewViewpoint(), s.terrain().bounds(), w,
                               h, s.scenario().camera.fovY);
    };
    s.setPlayback(scene::playbackOf(clock));
    const double warm0 = wall.now();
    const math::Camera first = cameraAt(clock.current());
    for (int k = 0; k < 60000 && (k == 0 || !s.terrain().settled()) && wall.now() - warm0 < 60;
         ++k) {
        s.prepare(first, clock.current());
        usleep(1000);
    }
    s.drawFrame(first, clock.current(), w, h);  // compiles the programs
    glFinish();
    r["warmup_seconds"] = wall.now() - warm0;

    std::vector<double> ms;
    std::vector<bench::PhaseSample> phases;
    int missing = 0, held = 0, hits = 0, steps = 0, maxDepth = 0, wraps = 0;
    std::int32_t lastShown = -1;
    const double start = wall.now();
    double last = start;
    while (wall.now() - start < seconds) {
        const double now = wall.now();
        const double dt = now - last;
        last = now;
        const bool ready = !s.terrain().frameInfo().holdingSequence;
        const auto step = clock.advance(dt, ready);
        wraps += step.wrapped;
        s.setPlayback(scene::playbackOf(clock));
        const double t0 = wall.now(), cpu0 = bench::processCpuMs();
        app::FrameRecord rec = s.drawFrame(cameraAt(step.time), step.time, w, h);
        glFinish();
        rec.frameMs = (wall.now() - t0) * 1000.0;
        const double cpuMs = bench::processCpuMs() - cpu0;
        // As play does: the tiles of the view the camera path reaches in two seconds.
        s.terrain().prefetch(cameraAt(clock.predict(2.0)));
        ms.push_back(rec.frameMs);
        phases.push_back(bench::phaseSample(rec, rec.frameMs, cpuMs));
        const auto& f = s.terrain().frameInfo();
        missing += f.sequenceTilesMissing > 0;
        held += f.holdingSequence;
        hits += int(f.prefetchHits);
        maxDepth = std::max(maxDepth, int(f.prefetchDepth));
        if (f.shownFrameA >= 0 && f.shownFrameA != lastShown) {
            steps += lastShown >= 0;
            lastShown = f.shownFrameA;
        }
    }
    const double p50 = app::percentile(ms, 50), p99 = app::percentile(ms, 99);
    r["frames"] = ms.size();
    r["fps"] = double(ms.size()) / std::max(1e-9, wall.now() - start);
    r["frame_ms"] = {{"p50", p50}, {"p95", app::percentile(ms, 95)}, {"p99", p99}};
    r.update(bench::phaseReport(phases));
    r["p99_over_median"] = p99 / std::max(1e-9, p50);
    r["p99_within_1_5x_median"] = p99 <= 1.5 * p50;
    r["frames_with_missing_sequence_tiles"] = missing;
    r["held_frames"] = held;
    r["prefetch_hits"] = hits;
    r["frame_steps_shown"] = steps;
    r["loop_restarts"] = wraps;
    r["max_prefetch_depth"] = maxDepth;
    r["data_seconds_played"] = clock.current() - s.startTime();

    // Baseline: the fill bound with the same texture fetches per pixel (sequences fetch two
    // frames), in the same run and at the same size.
    int fetches = 1;
    for (const auto& l : s.scenario().layers)
        if (l.enabled) fetches += l.kind == config::LayerKind::Sequence ? 2 : 1;
    opened->reset();
    target->bind();
    if (auto fill = render::FillBound::create(fetches)) {
        std::vector<double> fb;
        for (int i = 0; i < 30; ++i) {
            const double t0 = wall.now();
            glClear(GL_COLOR_BUFFER_BIT);
            fill->draw();
            glFinish();
            fb.push_back((wall.now() - t0) * 1000.0);
        }
        const double b = app::percentile(fb, 50);
        r["fill_bound_ms"] = b;
        r["fill_bound_fetches_per_pixel"] = fetches;
        r["ratio_to_fill_bound"] = p50 / std::max(1e-9, b);
        r["fill_bound_fraction"] = b / std::max(1e-9, p50);
        r["within_1_5x_fill_bound"] = p50 <= 1.5 * b;
    }
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> scenarios;
    std::vector<std::pair<int, int>> sizes{{1280, 720}, {1920, 1080}};
    double seconds = 10.0, anugaRate = 10.0;
    std::string anuga;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) {
            seconds = std::max(1.0, std::atof(argv[++i]));
        } else if (!std::strcmp(argv[i], "--anuga") && i + 1 < argc) {
            anuga = argv[++i];
        } else if (!std::strcmp(argv[i], "--rate") && i + 1 < argc) {
            anugaRate = std::atof(argv[++i]);
        } else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
            sizes.clear();
            const std::string list = argv[++i];
            for (std::size_t p = 0; p <= list.size();) {
                auto q = list.find(',', p);
                if (q == std::string::npos) q = list.size();
                if (auto wh = parseSize(list.substr(p, q - p))) sizes.push_back(*wh);
                p = q + 1;
            }
        } else if (argv[i][0] == '-') {
            std::fprintf(stderr,
                         "usage: bench-replay [SCENARIO ...] [--sizes WxH,...] [--seconds S] "
                         "[--anuga FILE.sww] [--rate R]\n");
            return 2;
        } else {
            scenarios.push_back(argv[i]);
        }
    }
    if (scenarios.empty()) scenarios.push_back("scenarios/demo/rainier.json");
    auto headless = bench::openHeadlessGl();
    if (!headless) return 3;
    const gl::Caps* caps = &headless->caps;

    nlohmann::json out;
    out["benchmark"] = "replay";
    out["renderer"] = caps->renderer;
    out["seconds_per_run"] = seconds;
    std::vector<std::pair<std::string, double>> runs;
    for (const auto& s : scenarios) runs.push_back({s, 0.0});
    fs::path tmp;
    std::error_code exists;
    if (!anuga.empty() && !fs::exists(anuga, exists)) {
        out["anuga_skipped"] = anuga + " not present";
    } else if (!anuga.empty()) {
        tmp = fs::temp_directory_path() / ("kiosk-bench-replay-" + std::to_string(::getpid()));
        std::string error;
        const std::string sc = prepareAnuga(anuga, tmp, error);
        if (sc.empty())
            out["anuga_error"] = error;
        else
            runs.push_back({sc, anugaRate});
    }
    for (const auto& [scenario, rate] : runs)
        for (auto [w, h] : sizes)
            out["results"].push_back(replay(scenario, w, h, seconds, rate, *caps));
    out["peak_rss_mb"] = peakRssMb();
    if (!tmp.empty()) {
        std::error_code ec;
        fs::remove_all(tmp, ec);
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
