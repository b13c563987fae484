// Both sides of a comparison lens step together (issue 19): with run B's store slowed (the
// loader's test hook delays only its tiles), every frame drawn while the clock runs shows the
// same step outside the lens (run A) as inside it (run B): the lens shows a new step only when
// both sides' frames are complete for the view, and neither side steps alone.
#include "tests/scenario/ComparisonFixture.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>

namespace kiosk::test {
namespace {

using namespace compare;

/**
 * Index of the colour in `refs` within 6 DN of `px`; -1 for the bare terrain's colour (no step
 * drawn); -2 for anything else (the terrain itself not drawn there yet: nothing to judge).
 */
int decode(const std::vector<glm::ivec3>& refs, const glm::ivec3& bare, const std::uint8_t* px) {
    const auto near = [px](const glm::ivec3& c) {
        int d = 0;
        for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(px[k]) - c[k]));
        return d <= 6;
    };
    for (std::size_t k = 0; k < refs.size(); ++k)
        if (near(refs[k])) return int(k);
    return near(bare) ? -1 : -2;
}

class ComparisonSync : public ComparisonTest {};

TEST_F(ComparisonSync, NeitherSideStepsAloneWhenRunBIsSlow) {
    const std::string text =
        scenario(kRuns, R"({ "id": "cmp", "kind": "comparison", "center": [500960, 4999040],
                             "radius": 500, "inside": ["B"], "outside": ["A"] })");
    // Each side's colour at every step, read once everything is resident.
    std::vector<glm::ivec3> refA, refB;
    {
        auto s = open("sync-ref.json", text);
        ASSERT_TRUE(s);
        const math::Camera cam = camera(*s);
        const glm::ivec2 in = project(cam, kCentreX, kCentreY, kW, kH);
        const glm::ivec2 out = project(cam, kWest + 150, kNorth - 150, kW, kH);
        for (int k = 0; k < kFrames; ++k) {
            const gl::Image img = settled(*s, k);
            const auto *a = img.pixel(out.x, out.y), *b = img.pixel(in.x, in.y);
            refA.emplace_back(a[0], a[1], a[2]);
            refB.emplace_back(b[0], b[1], b[2]);
        }
    }
    for (int i = 0; i < kFrames; ++i)  // decoding needs six distinct colours per side
        for (int j = 0; j < i; ++j) {
            const glm::ivec3 da = glm::abs(refA[std::size_t(i)] - refA[std::size_t(j)]);
            const glm::ivec3 db = glm::abs(refB[std::size_t(i)] - refB[std::size_t(j)]);
            ASSERT_GT(std::max({da.r, da.g, da.b}), 12) << "steps " << i << ", " << j;
            ASSERT_GT(std::max({db.r, db.g, db.b}), 12) << "steps " << i << ", " << j;
        }
    glm::ivec3 bare;  // the terrain without either run
    {
        auto s = open("sync-bare.json", scenario("", ""));
        ASSERT_TRUE(s);
        const glm::ivec2 out = project(camera(*s), kWest + 150, kNorth - 150, kW, kH);
        const gl::Image img = settled(*s, 0);
        bare = glm::ivec3(img.pixel(out.x, out.y)[0], img.pixel(out.x, out.y)[1],
                          img.pixel(out.x, out.y)[2]);
    }
    // Run B's tiles take 150 ms each to load, run A's arrive at once.
    setenv("GEOKIOSK_TEST_LOAD_DELAY_MS", "150", 1);
    setenv("GEOKIOSK_TEST_LOAD_DELAY_STORE", "b", 1);
    auto s = open("sync.json", text);
    unsetenv("GEOKIOSK_TEST_LOAD_DELAY_MS");
    unsetenv("GEOKIOSK_TEST_LOAD_DELAY_STORE");
    ASSERT_TRUE(s);
    const math::Camera cam = camera(*s);
    const glm::ivec2 in = project(cam, kCentreX, kCentreY, kW, kH);
    const glm::ivec2 out = project(cam, kWest + 150, kNorth - 150, kW, kH);
    auto rt = makeTarget(kW, kH);
    int frames = 0, judged = 0, held = 0, stepsSeen = 0, last = -1;
    // The clock moves to the next step as soon as the lens showed the previous one: run B's next
    // frame is then still loading (at most prefetched for part of its 150 ms), run A's is there.
    for (int k = 0; k < kFrames; ++k) {
        const double t = s->startTime() + 3600.0 * k + 60.0;
        for (int f = 0; f < 600; ++f, ++frames) {
            rt.bind();
            s->drawFrame(cam, t, kW, kH);
            held += s->terrain().frameInfo().holdingSequence ? 1 : 0;
            const gl::Image img = rt.readColor();
            const int a = decode(refA, bare, img.pixel(out.x, out.y));
            const int b = decode(refB, bare, img.pixel(in.x, in.y));
            if (a == -2 || b == -2) {  // the terrain mesh is still loading at a probe
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
                continue;
            }
            ++judged;
            ASSERT_EQ(a, b) << "frame " << frames << " (clock at step " << k
                            << "): run A outside shows step " << a << ", run B inside step " << b;
            if (a >= 0 && a != last) ++stepsSeen, last = a;
            if (a == k) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        ASSERT_EQ(last, k) << "the lens never showed step " << k;
    }
    EXPECT_EQ(stepsSeen, kFrames) << "the lens must step as the clock moves";
    EXPECT_GT(held, 10) << "run B was not slow enough to make run A wait";
    EXPECT_GT(judged, frames / 2) << "most frames must show terrain at both probes";
}

}  // namespace
}  // namespace kiosk::test
