// A kiosk re-opens its scenario for weeks (hot reload, playlist steps, store swaps): opening,
// drawing and closing a session must leave nothing behind (issue 15's soak goal). RSS is read
// with no session alive, so what it gains after the first cycles is kept across sessions.
#include "runtime/app/Session.h"
#include "runtime/service/ServiceState.h"
#include "tests/support/DemoStoreTest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <malloc.h>
#include <thread>
#include <vector>

namespace kiosk::app {
namespace {

constexpr int kW = 64, kH = 36;

class SessionReopen : public test::DemoStoreTest {
protected:
    /** Open the demo, play `frames` frames of its tour (tiles load and are evicted), close. */
    void cycle(gl::RenderTarget& rt, int frames) {
        auto s = Session::open("scenarios/demo/rainier.json", mCaps);
        ASSERT_TRUE(s.ok()) << s.diagnostics.format();
        Session& session = **s;
        for (int i = 0; i < frames; ++i) {
            const double t = session.startTime() + 600.0 * i;
            auto vp = session.viewpointAt(t, "");
            ASSERT_TRUE(vp.ok());
            rt.bind();
            session.drawFrame(makeCamera(*vp, session.terrain().bounds(), kW, kH, 45), t, kW, kH);
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
    }
};

TEST_F(SessionReopen, ReopeningLeavesNothingBehind) {
    auto rt = gl::RenderTarget::create(kW, kH);
    ASSERT_TRUE(rt.ok());
    std::vector<double> rssMb;
    const int cycles =
        std::getenv("KIOSK_TEST_CYCLES") ? std::atoi(std::getenv("KIOSK_TEST_CYCLES")) : 16;
    ASSERT_GE(cycles, 8);
    for (int c = 0; c < cycles; ++c) {
        cycle(*rt, 40);
        if (HasFatalFailure()) return;
        glFinish();      // llvmpipe frees deleted textures and buffers once their commands ran
        malloc_trim(0);  // as the kiosk does after a swap (KioskHooks::frameDone)
        rssMb.push_back(double(service::readRssBytes()) / (1 << 20));
        std::printf("cycle %d: RSS %.2f MB, heap in use %.2f MB\n", c, rssMb.back(),
                    double(service::readHeapInUseBytes()) / (1 << 20));
    }
    // The first two cycles fill one-time state (GDAL/SQLite/Mesa registries, shader variants).
    // After them single readings still jump by 1-4 MB for a cycle (llvmpipe's scene bins and
    // freed texture storage it keeps), and under a loaded ctest -j2 the jumps cluster, so the
    // growth is the Theil-Sen slope (median of all pairwise slopes) over the later cycles: a
    // leak raises every later reading, a jump moves only the pairs through it. A 1 MB block
    // leaked per re-open measures 1.02 MB; clean runs two at a time measured 0.01-0.29.
    // The soak benchmark (bench/kiosk) measures the small rates; valgrind (memcheck) finds the
    // same lost and reachable bytes after 2 and 6 cycles.
    std::vector<double> slopes;
    for (int a = 2; a < cycles; ++a)
        for (int b = a + 1; b < cycles; ++b) slopes.push_back((rssMb[b] - rssMb[a]) / (b - a));
    std::nth_element(slopes.begin(), slopes.begin() + slopes.size() / 2, slopes.end());
    const double slope = slopes[slopes.size() / 2];
    std::printf("RSS growth: %.3f MB per re-open (Theil-Sen over cycles 2-%d)\n", slope,
                cycles - 1);
    EXPECT_LT(slope, 0.6) << "RSS grows by " << slope << " MB per session re-open";
}

}  // namespace
}  // namespace kiosk::app
