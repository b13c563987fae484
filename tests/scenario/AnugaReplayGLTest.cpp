// Replay of a real ANUGA flood (issue 6): the SWW model's bed imported as the terrain and its
// depth as a sequence on the same grid, played through the scene at 1x and 10x with fixed
// simulated frame times. After warm-up no frame may miss a sequence tile (the prefetch planner
// keeps the playhead's next frames resident, across the loop restart too) and no frame may mix
// time steps.
#include "runtime/anim/FrameBracket.h"
#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Session.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 192, kHeight = 108;
constexpr double kFrameSeconds = 1.0 / 30.0;  // simulated wall time per frame

class AnugaReplay : public test::EglTest {
protected:
    static void SetUpTestSuite() {
        sSww = test::sharedData("anuga_sww_flood_timeseries/cairns.sww");
        if (sSww.empty()) return;
        sDir = fs::temp_directory_path() / ("kiosk-anuga-" + std::to_string(::getpid()));
        fs::create_directories(sDir);
        import::ImportOptions o;
        o.store = sDir / "cairns.gpkg";
        o.quiet = true;
        o.name = "elevation";
        sImport = import::importElevation(sSww, o).format();
        o.name = "flood";
        o.start = *parseIso8601("2026-03-14T00:00:00Z");
        o.wetThreshold = 0.01;
        if (sImport.empty()) sImport = import::importSequence({sSww}, o).format();
        std::ofstream(sDir / "replay.json") << R"({ "version": 1, "title": "Cairns",
            "stores": { "s": "cairns.gpkg" },
            "terrain": { "store": "s", "tauGeom": 1, "tauTex": 1 },
            "transferFunctions": { "depth": { "units": "m", "stops": [
                { "value": 0, "color": "#c6dbef00" }, { "value": 0.05, "color": "#6baed6" },
                { "value": 8, "color": "#08306b" } ] } },
            "layers": [ { "id": "flood", "kind": "sequence",
                          "source": { "store": "s", "sequence": "flood" },
                          "transfer": "depth", "nodataAs": 0 } ] })";
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        if (!sDir.empty()) fs::remove_all(sDir, ec);
    }

    struct Replay {
        int frames = 0;
        int missingFrames = 0;  ///< frames with wanted sequence tiles not resident
        int heldFrames = 0;
        int mixedFrames = 0;
        int behindClock = 0;  ///< frames whose shown pair is not the clock's bracket
        int prefetchHits = 0;
        int maxDepth = 0;
        bool wrapped = false;
        std::set<int> shown;
    };

    /** Play `frames` frames at `rate` from `initial` (data seconds after the start). */
    Replay replay(double rate, double initial, int frames) {
        Replay out;
        EXPECT_EQ(sImport, "");
        auto opened = Session::open(sDir / "replay.json", mCaps);
        EXPECT_TRUE(opened.ok()) << opened.diagnostics.format();
        if (!opened) return out;
        Session& s = **opened;
        const auto times = s.terrain().sequenceKeyTimes();
        EXPECT_GE(times.size(), 20u);
        anim::ClockSettings cs;
        cs.start = s.startTime();
        cs.end = s.endTime();
        cs.rate = rate;
        cs.range = anim::RangeMode::Loop;
        cs.waitForData = true;
        cs.initial = s.startTime() + initial;
        auto clock = anim::ScenarioClock::create(cs);
        EXPECT_TRUE(clock.ok());
        if (!clock) return out;
        auto vp = s.viewpointAt(clock->current(), "");
        EXPECT_TRUE(vp.ok());
        const math::Camera cam = makeCamera(*vp, s.terrain().bounds(), kWidth, kHeight, 45.0);
        auto rt = makeTarget(kWidth, kHeight);

        // Warm-up: the first view and its pair (a kiosk shows its first frame once loaded).
        s.setPlayback(scene::playbackOf(*clock));
        test::settleView(s, cam, clock->current());
        const auto loop0 = std::chrono::steady_clock::now();
        for (int i = 0; i < frames; ++i) {
            const bool ready = !s.terrain().frameInfo().holdingSequence;
            const auto step = clock->advance(kFrameSeconds, ready);
            out.wrapped = out.wrapped || step.wrapped;
            s.setPlayback(scene::playbackOf(*clock));
            rt.bind();
            s.drawFrame(cam, step.time, kWidth, kHeight);
            glFinish();  // as play does: the frame is really drawn before the next one
            const scene::SceneFrameInfo& f = s.terrain().frameInfo();
            ++out.frames;
            out.missingFrames += f.sequenceTilesMissing > 0;
            out.heldFrames += f.holdingSequence;
            out.mixedFrames += f.mixedSequenceFrames;
            out.prefetchHits += int(f.prefetchHits);
            out.maxDepth = std::max(out.maxDepth, int(f.prefetchDepth));
            const auto b = anim::bracketFrames(times, step.time, anim::Interpolation::Data);
            if (f.shownFrameA != int(b.i0) || (b.i1 != b.i0 && f.shownFrameB != int(b.i1)))
                ++out.behindClock;
            out.shown.insert(f.shownFrameA);
        }
        std::printf("replay at %gx: %d frames in %.2f s, prefetch hits %d, max depth %d\n", rate,
                    frames,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - loop0).count(),
                    out.prefetchHits, out.maxDepth);
        return out;
    }

    static inline std::string sSww;
    static inline fs::path sDir;
    static inline std::string sImport;
};

TEST_F(AnugaReplay, OneTimesRateNeverMissesATile) {
    if (sSww.empty()) GTEST_SKIP() << "../shared/data/anuga_sww_flood_timeseries absent";
    // 11.5 s of playback from 1 s before the 100 s frame: two step changes at 1x (frames 10 s).
    const Replay r = replay(1.0, 99.0, 345);
    EXPECT_EQ(r.missingFrames, 0);
    EXPECT_EQ(r.heldFrames, 0);
    EXPECT_EQ(r.mixedFrames, 0);
    EXPECT_EQ(r.behindClock, 0);
    EXPECT_GE(r.shown.size(), 3u) << "the replay never stepped";
    EXPECT_GE(r.prefetchHits, 2) << "the next frames were not prefetched";
}

TEST_F(AnugaReplay, TenTimesRateNeverMissesATileAcrossTheLoop) {
    if (sSww.empty()) GTEST_SKIP() << "../shared/data/anuga_sww_flood_timeseries absent";
    // 10 s of playback at 10x from 440 s: 100 s of data, through the loop restart at 500 s.
    const Replay r = replay(10.0, 440.0, 300);
    EXPECT_TRUE(r.wrapped) << "the replay never reached the loop end";
    EXPECT_EQ(r.missingFrames, 0);
    EXPECT_EQ(r.heldFrames, 0);
    EXPECT_EQ(r.mixedFrames, 0);
    EXPECT_EQ(r.behindClock, 0);
    EXPECT_GE(r.shown.size(), 9u) << "the replay did not step through the frames";
    EXPECT_GE(r.prefetchHits, 8);
    EXPECT_GE(r.maxDepth, 1);
}

}  // namespace
}  // namespace kiosk::app
