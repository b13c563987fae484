#include "runtime/wall/FollowerSync.h"
#include "runtime/wall/SwapBarrier.h"
#include "runtime/wall/ZmqTransport.h"

#include <gtest/gtest.h>

#include <thread>

namespace kiosk::wall {
namespace {

using namespace std::chrono_literals;

// The transport on loopback in one process: a leader and two followers run the real barrier
// for 20 frames; one follower stops answering after frame 10 and the wall keeps swapping.
TEST(ZmqTransportTest, BarrierOnLoopback) {
    auto leader = LeaderTransport::bind({"tcp://127.0.0.1:*", "tcp://127.0.0.1:*", 50.0});
    ASSERT_TRUE(leader) << leader.diagnostics.format();
    const auto [stateEp, readyEp] = (*leader)->endpoints();
    const SyncSettings sync{stateEp, readyEp, 50.0};
    // A second leader on the same endpoint is a clear error, not a crash.
    auto clash = LeaderTransport::bind(sync);
    ASSERT_FALSE(clash);
    EXPECT_TRUE(clash.diagnostics.has("WALL_ENDPOINT"));

    auto followerLoop = [&](std::uint32_t screen, std::uint64_t lastFrame,
                            std::vector<std::uint64_t>* swaps) {
        auto t = FollowerTransport::connect(sync);
        ASSERT_TRUE(t);
        FollowerSync f(screen, 5.0);
        const auto until = std::chrono::steady_clock::now() + 10s;
        while (!f.stopped() && std::chrono::steady_clock::now() < until) {
            if (auto m = (*t)->receive(5ms)) {
                const auto type = messageType(*m);
                if (type == MessageType::State) f.onState(*decodeState(*m), 0.0);
                if (type == MessageType::Release) f.onRelease(*decodeRelease(*m));
                if (type == MessageType::Stop) f.onStop();
            }
            if (auto s = f.takeStateToDraw()) {
                if (s->frame > lastFrame) continue;  // "dies": stops answering
                if (auto r = f.drawn(true, true, 0)) (*t)->send(encode(*r));
            }
            if (f.swapDue()) swaps->push_back(f.swapped());
        }
    };
    std::vector<std::uint64_t> swapsA, swapsB;
    std::thread a(followerLoop, 1, 1000, &swapsA), b(followerLoop, 2, 10, &swapsB);

    SwapBarrier barrier({1, 2}, 0.05);
    auto now = [] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
    };
    std::vector<bool> byDeadline;
    for (std::uint64_t frame = 1; frame <= 20; ++frame) {
        FrameState s;
        s.frame = frame;
        // The first frame waits for both to join (republishing: PUB drops before a subscriber
        // connects).
        barrier.begin(frame, now(), frame == 1 ? 5.0 : 0.05);
        barrier.leaderReady(true);
        double lastSend = -1;
        while (!barrier.releasable(now())) {
            if (now() - lastSend > 0.02) {
                (*leader)->publish(encode(s));
                lastSend = now();
            }
            if (auto m = (*leader)->receive(2ms))
                if (auto r = decodeReady(*m)) barrier.onReady(*r);
        }
        const Release r = barrier.release();
        byDeadline.push_back(r.byDeadline);
        (*leader)->publish(encode(r));
    }
    (*leader)->publish(encodeStop());
    a.join();
    b.join();
    EXPECT_EQ(swapsA.size(), 20u);
    ASSERT_GE(swapsB.size(), 10u);
    for (std::uint64_t i = 0; i < 10; ++i) EXPECT_EQ(swapsB[i], i + 1);
    // Frame 11 waited for the silent node until the deadline; from frame 12 on it is dropped.
    EXPECT_FALSE(byDeadline[9]);
    EXPECT_TRUE(byDeadline[10]);
    for (std::size_t i = 11; i < 20; ++i) EXPECT_FALSE(byDeadline[i]) << i;
}

}  // namespace
}  // namespace kiosk::wall
