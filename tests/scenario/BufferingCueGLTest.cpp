// The picture never lies about time (issue 15): when a sequence holds an older step because its
// tiles are late, the time label shows the time actually drawn and a "buffering" cue. Pixels
// read back from llvmpipe: the label's text of a starved frame is the text of a frame settled at
// the held time, followed by the cue, and not the text of the time that was asked for.
#include "runtime/app/ImageOutput.h"
#include "runtime/app/Session.h"
#include "runtime/render/FontAtlas.h"
#include "tests/support/DemoStoreTest.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>
#include <vector>

namespace kiosk::app {
namespace {

constexpr int kW = 960, kH = 600;  // a 15 px overlay font: glyphs with solid strokes
constexpr int kBand = 60;          // rows holding the top-left time label at this size

/** Text pixels of the label band: the overlay's text is opaque white (grey where anti-aliased);
 *  the panel behind it is dark and the sky above the overview is blue-grey. */
struct TextMask {
    std::vector<bool> on = std::vector<bool>(std::size_t(kW) * kBand, false);
    int count = 0, x0 = kW, x1 = -1;
    bool at(int x, int y) const { return on[std::size_t(y) * kW + std::size_t(x)]; }
};

TextMask textMask(const gl::Image& img) {
    TextMask m;
    for (int y = 0; y < kBand && y < img.height; ++y)  // readColor(): top row first
        for (int x = 0; x < kW && x < img.width; ++x) {
            const auto* p = img.pixel(x, y);
            const int lo = std::min({p[0], p[1], p[2]}), hi = std::max({p[0], p[1], p[2]});
            if (lo < 150 || hi - lo > 12) continue;
            m.on[std::size_t(y) * kW + std::size_t(x)] = true;
            ++m.count;
            m.x0 = std::min(m.x0, x);
            m.x1 = std::max(m.x1, x);
        }
    return m;
}

/** Pixels set in exactly one of the masks, over columns [0, toX]. */
int mismatches(const TextMask& a, const TextMask& b, int toX) {
    int n = 0;
    for (int y = 0; y < kBand; ++y)
        for (int x = 0; x <= toX && x < kW; ++x) n += a.at(x, y) != b.at(x, y);
    return n;
}

class BufferingCue : public test::DemoStoreTest {
protected:
    /** The demo with only the time label ("HH:MM", top-left) on: nothing else bright there. */
    std::unique_ptr<Session> open(bool timeLabel = true) {
        auto s = Session::open("scenarios/demo/rainier.json", mCaps, [&](config::Scenario& sc) {
            sc.overlays.title.enabled = false;
            sc.overlays.legends.clear();
            sc.overlays.progress.enabled = false;
            sc.overlays.timeLabel.enabled = timeLabel;
            sc.overlays.timeLabel.position = config::Corner::TopLeft;
            sc.overlays.timeLabel.format = "%H:%M";
            sc.overlays.timeLabel.showOffset = false;
        });
        EXPECT_TRUE(s.ok()) << s.diagnostics.format();
        return s.ok() ? std::move(*s.value) : nullptr;
    }
    math::Camera camera(Session& s) {
        auto vp = s.viewpointAt(s.startTime(), "overview");
        EXPECT_TRUE(vp.ok());
        return makeCamera(*vp, s.terrain().bounds(), kW, kH, 45);
    }
    /** Every tile of the view at `time` resident (render's deterministic wait), paused clock:
     *  no sequence frames are fetched ahead of `time`. */
    void settle(Session& s, const math::Camera& cam, double time) {
        scene::Playback paused;
        paused.paused = true;
        s.setPlayback(paused);
        test::settleView(s, cam, time);
    }
    gl::Image draw(Session& s, const math::Camera& cam, double time) {
        auto rt = gl::RenderTarget::create(kW, kH);
        EXPECT_TRUE(rt.ok());
        if (!rt.ok()) return {};
        rt->bind();
        s.drawFrame(cam, time, kW, kH);
        return rt->readColor();
    }
};

TEST_F(BufferingCue, StarvedFrameLabelsTheHeldTimeAndSaysBuffering) {
    auto s = open();
    ASSERT_TRUE(s);
    const math::Camera cam = camera(*s);
    const double before = s->startTime() + 3 * 3600.0;  // a step of the flood sequence
    const double asked = s->startTime() + 7 * 3600.0;   // "07:00", tiles never requested yet

    // Jump four hours in one frame: the new step's tiles are only requested by this frame, so
    // the sequence holds a pair of the earlier time.
    settle(*s, cam, before);
    draw(*s, cam, before);
    ASSERT_FALSE(s->terrain().frameInfo().holdingSequence);
    const gl::Image starved = draw(*s, cam, asked);
    const auto& info = s->terrain().frameInfo();
    ASSERT_TRUE(info.holdingSequence)
        << "the jump did not starve the sequence: test proves nothing";
    const double held = info.heldDataTime;  // the time the held pair draws
    ASSERT_GE(held, before);
    ASSERT_LE(held, before + 3600.0);

    // Reference labels: frames settled at the held time and at the asked-for time.
    settle(*s, cam, held);
    const gl::Image atHeld = draw(*s, cam, held);
    ASSERT_FALSE(s->terrain().frameInfo().holdingSequence);
    settle(*s, cam, asked);
    const gl::Image atAsked = draw(*s, cam, asked);
    ASSERT_FALSE(s->terrain().frameInfo().holdingSequence);
    auto plain = open(false);
    ASSERT_TRUE(plain);
    settle(*plain, cam, held);
    const gl::Image noLabel = draw(*plain, cam, held);

    const TextMask m0 = textMask(noLabel), mh = textMask(atHeld), ms = textMask(starved),
                   ma = textMask(atAsked);
    ASSERT_EQ(m0.count, 0) << "bright pixels without a label: the mask would not be text";
    ASSERT_GT(mh.count, 50) << "no time label text found";
    // The time text: the starved label writes the held pair's time, not the one asked for.
    EXPECT_LE(mismatches(ms, mh, mh.x1), mh.count / 50) << "starved label != label at held time";
    EXPECT_GT(mismatches(ma, mh, mh.x1), mh.count / 5) << "07:00 and the held time look alike";
    EXPECT_GT(mismatches(ms, ma, mh.x1), mh.count / 5) << "starved label shows the asked time";

    // The cue: text after the time, as wide as "buffering" in the overlay font; settled frames
    // have none.
    auto font =
        render::FontAtlas::build(render::FontAtlas::defaultFontPath(), std::clamp(kH / 40, 10, 40));
    ASSERT_TRUE(font.ok()) << font.diagnostics.format();
    const float cueWidth = font->measure("buffering");
    int cueX0 = kW, cueCount = 0;
    for (int y = 0; y < kBand; ++y)
        for (int x = mh.x1 + 1; x < kW; ++x)
            if (ms.at(x, y)) {
                cueX0 = std::min(cueX0, x);
                ++cueCount;
            }
    ASSERT_GT(cueCount, 30) << "no buffering cue after the time";
    EXPECT_NEAR(ms.x1 - cueX0 + 1, cueWidth, 4.0);
    EXPECT_LT(std::abs(ma.x1 - mh.x1), 4) << "a settled 07:00 label has no cue either";
    if (::testing::Test::HasFailure() || std::getenv("KIOSK_TEST_KEEP_PNG")) {  // to look at
        Diagnostics d;
        writePng("buffering-starved.png", starved, d);
        writePng("buffering-held.png", atHeld, d);
    }
}

}  // namespace
}  // namespace kiosk::app
