// Issue 14: the steady-state frame loop makes no heap allocations. A counting global operator
// new (this executable only) counts allocations made on the test thread -- the render thread --
// while it runs the same per-frame calls as `play`: playback state, drawFrame (tile selection,
// completions, sequence pairs and prefetch planning, layer compositing, overlays with the time
// label and legend) and the camera-path prefetch. The loader thread's work (decoding tiles) is
// not the frame loop and is not counted; nor is the GL driver's own malloc.
#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/Session.h"
#include "tests/support/EglTestContext.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <execinfo.h>
#include <filesystem>
#include <new>
#include <thread>
#include <unistd.h>

namespace {
thread_local bool tCounting = false;
std::atomic<std::uint64_t> gAllocations{0};
// KIOSK_ALLOC_TRACE=N prints the call stacks of the first N counted allocations (to find them).
std::atomic<int> gTraceLeft{0};

void trace() {
    if (gTraceLeft.fetch_sub(1) <= 0) return;
    void* frames[24];
    const int n = backtrace(frames, 24);
    static const char kSep[] = "---- allocation in the frame loop:\n";
    [[maybe_unused]] auto w = ::write(2, kSep, sizeof kSep - 1);
    backtrace_symbols_fd(frames, n, 2);  // writes directly, no malloc
}

void* countedAlloc(std::size_t n) {
    if (tCounting) {
        gAllocations.fetch_add(1, std::memory_order_relaxed);
        tCounting = false;
        trace();
        tCounting = true;
    }
    return std::malloc(n ? n : 1);
}
void* countedAlignedAlloc(std::size_t n, std::align_val_t a) {
    if (tCounting) gAllocations.fetch_add(1, std::memory_order_relaxed);
    const std::size_t align = std::size_t(a);
    return std::aligned_alloc(align, (n + align - 1) / align * align);
}
}  // namespace

void* operator new(std::size_t n) {
    if (void* p = countedAlloc(n)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
    if (void* p = countedAlloc(n)) return p;
    throw std::bad_alloc();
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    return countedAlloc(n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
    return countedAlloc(n);
}
void* operator new(std::size_t n, std::align_val_t a) {
    if (void* p = countedAlignedAlloc(n, a)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) {
    if (void* p = countedAlignedAlloc(n, a)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
    std::free(p);
}

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;

class FrameAlloc : public test::EglTest {};

constexpr int kWidth = 160, kHeight = 90;  // small: the test is about allocations, not pixels
constexpr int kFrames = 1000;
constexpr double kDt = 1.0 / 60.0;     // wall seconds per frame, as a 60 Hz kiosk
constexpr double kAheadSeconds = 2.0;  // play's camera-path prefetch horizon

TEST_F(FrameAlloc, SteadyStateFrameLoopDoesNotAllocate) {
    if (!fs::exists("data/generated/rainier.gpkg"))
        KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA", "demo store missing: run tools/prepare-demo.sh");
    auto rt = gl::RenderTarget::create(kWidth, kHeight);
    ASSERT_TRUE(rt.ok());
    // Budgets that hold the whole demo: the counted pass replays frames that are all resident.
    auto opened = Session::open("scenarios/demo/rainier.json", mCaps, [](config::Scenario& s) {
        s.terrain.cacheBytes = 1ll << 30;
        s.terrain.gpuBytes = 1ll << 30;
    });
    ASSERT_TRUE(opened.ok()) << opened.diagnostics.format();
    Session& s = **opened.value;
    auto settings = s.clockSettings();
    auto created = anim::ScenarioClock::create(settings);
    ASSERT_TRUE(created.ok());
    rt->bind();

    // One pass of the play loop body over kFrames frames from +3 h (the flood rises, the sun
    // and the camera move, the time label changes every frame).
    const auto runPass = [&](bool counted) {
        anim::ScenarioClock clock = *created.value;
        clock.seek(s.startTime() + 3 * 3600);
        std::uint64_t maxInFrame = 0, framesAllocating = 0;
        for (int i = 0; i < kFrames; ++i) {
            const std::uint64_t before = gAllocations.load();
            tCounting = counted;
            const double t = clock.advance(kDt, true).time;
            s.setPlayback(scene::playbackOf(clock));
            auto vp = s.viewpointAt(t, "");
            const math::Camera cam =
                makeCamera(*vp, s.terrain().bounds(), kWidth, kHeight, s.scenario().camera.fovY);
            s.drawFrame(cam, t, kWidth, kHeight);
            if (auto ahead = s.viewpointAt(clock.predict(kAheadSeconds), ""))
                s.terrain().prefetch(makeCamera(*ahead, s.terrain().bounds(), kWidth, kHeight,
                                                s.scenario().camera.fovY));
            tCounting = false;
            const std::uint64_t n = gAllocations.load() - before;
            maxInFrame = std::max(maxInFrame, n);
            framesAllocating += n > 0 ? 1 : 0;
            if (!counted && i % 10 == 0) {
                // Warm-up: let every tile of this frame (and its prefetch) arrive.
                for (int k = 0; k < 5000 && !s.terrain().settled(); ++k) {
                    std::this_thread::sleep_for(std::chrono::milliseconds(1));
                    s.prepare(cam, t);
                }
            }
        }
        return std::pair{framesAllocating, maxInFrame};
    };
    // Warm-up over the same frames: fills the cache (every 10th frame waits for its tiles and
    // the camera path's) and grows every reused buffer to its size.
    runPass(false);
    if (const char* n = std::getenv("KIOSK_ALLOC_TRACE")) {
        void* warm[1];
        backtrace(warm, 1);  // loads libgcc's unwinder now, not inside a counted allocation
        gTraceLeft = std::atoi(n);
    }
    const std::uint64_t total0 = gAllocations.load();
    const auto [framesAllocating, maxInFrame] = runPass(true);
    const std::uint64_t total = gAllocations.load() - total0;
    EXPECT_EQ(total, 0u) << framesAllocating << " of " << kFrames
                         << " steady-state frames allocated (max " << maxInFrame
                         << " allocations in one frame)";
    // The counter does see allocations on this thread (the test would pass vacuously otherwise).
    gTraceLeft = 0;
    tCounting = true;
    void* probe = ::operator new(64);  // an explicit call: never elided like a new-expression
    tCounting = false;
    ::operator delete(probe);
    EXPECT_EQ(gAllocations.load() - total0 - total, 1u);
}

}  // namespace
}  // namespace kiosk::app
