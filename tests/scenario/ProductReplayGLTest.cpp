// Derived products in the running scene (issue 19), on the ANUGA cairns run: a seek backwards
// shows the product at the new time (the same pixels as opening the scenario at that time),
// never the later state; with a slow loader a product never shows a state of another step than
// its frames (atomic like the sequences) and ends on the same pixels.
#include "runtime/app/Session.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160, kHeight = 90;

class ProductReplay : public test::EglTest {
protected:
    static void SetUpTestSuite() {
        sSww = test::sharedData("anuga_sww_flood_timeseries/cairns.sww");
        if (sSww.empty()) return;
        sDir = fs::temp_directory_path() / ("kiosk-productreplay-" + std::to_string(::getpid()));
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
        // The three time-accumulating products over the depth sequence; maximum first (the
        // layer frameInfo() reports).
        std::ofstream(sDir / "products.json") << R"({ "version": 1, "title": "Cairns",
            "stores": { "s": "cairns.gpkg" },
            "terrain": { "store": "s", "tauGeom": 1, "tauTex": 1 },
            "clock": { "start": "2026-03-14T00:00:00Z", "end": "2026-03-14T00:08:20Z", "paused": true },
            "transferFunctions": {
              "max": { "units": "m", "stops": [ { "value": 0, "color": "#fee5d9" }, { "value": 4, "color": "#a50f15" } ] },
              "t": { "units": "min", "stops": [ { "value": 0, "color": "#440154" }, { "value": 8, "color": "#fde725" } ] } },
            "layers": [
              { "id": "max", "kind": "maximum", "source": { "store": "s", "sequence": "flood" },
                "transfer": "max", "nodataAs": 0, "operation": { "type": "opacity", "opacity": 0.6 } },
              { "id": "arr", "kind": "arrival", "source": { "store": "s", "sequence": "flood" },
                "transfer": "t", "nodataAs": 0, "operation": { "type": "opacity", "opacity": 0.5 },
                "product": { "threshold": 1.0, "timeUnits": "min" } },
              { "id": "dur", "kind": "duration", "source": { "store": "s", "sequence": "flood" },
                "transfer": "t", "nodataAs": 0, "operation": { "type": "opacity", "opacity": 0.4 },
                "product": { "threshold": 2.0, "timeUnits": "min" } } ] })";
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        if (!sDir.empty()) fs::remove_all(sDir, ec);
    }
    void SetUp() override {
        test::EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        if (sSww.empty()) GTEST_SKIP() << "../shared/data/anuga_sww_flood_timeseries absent";
        ASSERT_EQ(sImport, "");
    }

    std::unique_ptr<Session> open() {
        auto s = Session::open(sDir / "products.json", mCaps);
        EXPECT_TRUE(s.ok()) << s.diagnostics.format();
        return s ? std::move(*s.value) : nullptr;
    }
    math::Camera camera(Session& s) {
        auto vp = s.viewpointAt(s.startTime(), "");
        EXPECT_TRUE(vp.ok());
        return makeCamera(*vp, s.terrain().bounds(), kWidth, kHeight, 45.0);
    }
    /** Settle at `offset` seconds after the start and read the pixels. */
    std::vector<std::uint8_t> settled(Session& s, gl::RenderTarget& rt, double offset) {
        const math::Camera cam = camera(s);
        const double t = s.startTime() + offset;
        EXPECT_TRUE(test::settleView(s, cam, t));
        rt.bind();
        s.drawFrame(cam, t, kWidth, kHeight);
        EXPECT_FALSE(s.terrain().frameInfo().mixedSequenceFrames);
        return rt.readColor().rgba;
    }
    static int maxDiff(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
        int worst = a.size() == b.size() ? 0 : 255;
        for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
            worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
        return worst;
    }

    static inline std::string sSww, sImport;
    static inline fs::path sDir;
};

TEST_F(ProductReplay, SeekBackShowsTheProductAtTheNewTime) {
    auto rt = makeTarget(kWidth, kHeight);
    std::vector<std::uint8_t> straight, later, back, forward;
    {
        auto s = open();
        ASSERT_TRUE(s);
        straight = settled(*s, rt, 155.0);  // mid-pair: frames 15, 16 at alpha 0.5
    }
    {
        auto s = open();
        ASSERT_TRUE(s);
        later = settled(*s, rt, 415.0);
        back = settled(*s, rt, 155.0);
        forward = settled(*s, rt, 415.0);
    }
    EXPECT_GT(maxDiff(straight, later), 40)
        << "the products did not change: the test proves nothing";
    EXPECT_EQ(maxDiff(back, straight), 0)
        << "a seek back shows another product than a straight replay";
    EXPECT_EQ(maxDiff(forward, later), 0);
}

TEST_F(ProductReplay, SlowTilesNeverMixAStateWithAnotherStep) {
    auto rt = makeTarget(kWidth, kHeight);
    std::vector<std::uint8_t> straight;
    {
        auto s = open();
        ASSERT_TRUE(s);
        straight = settled(*s, rt, 305.0);
    }
    setenv("GEOKIOSK_TEST_LOAD_DELAY_MS", "20", 1);
    auto s = open();
    unsetenv("GEOKIOSK_TEST_LOAD_DELAY_MS");
    ASSERT_TRUE(s);
    settled(*s, rt, 95.0);
    const math::Camera cam = camera(*s);
    int held = 0, frames = 0;
    std::int32_t first = -1, previous = -1;
    // Jump ahead: the product tiles of frame 30 arrive one by one behind the slow loader. The
    // maximum layer (the one frameInfo() reports) shows the old complete step until every tile
    // of the new one is resident, then the new one whole.
    for (; frames < 3000; ++frames) {
        rt.bind();
        s->drawFrame(cam, s->startTime() + 305.0, kWidth, kHeight);
        const auto& f = s->terrain().frameInfo();
        ASSERT_FALSE(f.mixedSequenceFrames) << "frame " << frames << " mixed steps";
        if (first < 0) first = f.shownFrameA;
        ASSERT_TRUE(f.shownFrameA == 9 || f.shownFrameA == 30)
            << "frame " << frames << " shows step " << f.shownFrameA;
        if (f.shownFrameA == 9) {
            ++held;
        } else if (previous != 30) {
            EXPECT_EQ(f.shownTilesIncomplete, 0u) << "the new step showed with a partial tile";
        }
        previous = f.shownFrameA;
        if (s->terrain().settled()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    EXPECT_GT(held, 0) << "the slow loader never made the product hold: the test proves nothing";
    EXPECT_EQ(first, 9);
    EXPECT_EQ(previous, 30);
    rt.bind();
    s->drawFrame(cam, s->startTime() + 305.0, kWidth, kHeight);
    EXPECT_EQ(maxDiff(rt.readColor().rgba, straight), 0);
}

// A sequence layer drawn with a product of its frames reads its value from the product's texel
// (one frame-pair read for both, docs/products.md): the same pixels as the sequence alone.
TEST_F(ProductReplay, SequenceSharingTheProductsFramesLooksTheSame) {
    const std::string head = R"({ "version": 1, "stores": { "s": "cairns.gpkg" },
        "terrain": { "store": "s", "tauGeom": 1, "tauTex": 1 },
        "clock": { "start": "2026-03-14T00:00:00Z", "end": "2026-03-14T00:08:20Z", "paused": true },
        "transferFunctions": { "d": { "units": "m", "stops": [ { "value": 0, "color": "#fee5d9" },
                                                              { "value": 4, "color": "#a50f15" } ] } },
        "layers": [ { "id": "flood", "kind": "sequence", "source": { "store": "s", "sequence": "flood" },
                      "transfer": "d", "nodataAs": 0 })";
    std::ofstream(sDir / "alone.json") << head << " ] }";
    std::ofstream(sDir / "shared.json")
        << head
        << R"(, { "id": "max", "kind": "maximum", "source": { "store": "s", "sequence": "flood" },
                     "transfer": "d", "nodataAs": 0, "operation": { "type": "opacity", "opacity": 0 } } ] })";
    auto rt = makeTarget(kWidth, kHeight);
    std::vector<std::uint8_t> alone[2], shared[2];
    for (const char* name : {"alone.json", "shared.json"}) {
        auto s = Session::open(sDir / name, mCaps);
        ASSERT_TRUE(s.ok()) << s.diagnostics.format();
        auto& out = std::string(name) == "alone.json" ? alone : shared;
        out[0] = settled(**s, rt, 155.0);  // mid-pair: frames 15, 16 at alpha 0.5
        out[1] = settled(**s, rt, 415.0);
    }
    EXPECT_GT(maxDiff(alone[0], alone[1]), 40) << "the two times look alike: proves nothing";
    EXPECT_LE(maxDiff(alone[0], shared[0]), 1);
    EXPECT_LE(maxDiff(alone[1], shared[1]), 1);
}

}  // namespace
}  // namespace kiosk::app
