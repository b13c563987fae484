// The KMS page-flip loop against a fake DRM/GBM device: mode set once, one flip per frame, every
// buffer released once it is off screen, vblank waits, timeouts and connector hot-unplug.
#include "runtime/platform/KmsFlipLoop.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <set>
#include <string>
#include <vector>

namespace kiosk::platform {
namespace {

/** @brief A GBM surface with `kBuffers` buffers and a CRTC, recording every call. */
class FakeKms final : public KmsDevice {
public:
    static constexpr int kBuffers = 3;
    std::vector<std::string> calls;
    std::set<int> locked;  // buffers handed out and not yet released
    int onScreen = -1;     // buffer the CRTC scans out
    int queued = -1;       // buffer of a flip not landed yet
    int next = 0;
    bool connected = true;
    bool flipFails = false;
    bool vblankStops = false;  // the next waits time out (hung display)
    int waitsTimedOut = 0;

    Buffer lockFrontBuffer() override {
        for (int k = 0; k < kBuffers; ++k) {
            const int i = (next + k) % kBuffers;
            if (locked.count(i)) continue;
            locked.insert(i);
            next = (i + 1) % kBuffers;
            calls.push_back("lock " + std::to_string(i));
            return id(i);
        }
        calls.push_back("lock failed");
        return nullptr;
    }
    void releaseBuffer(Buffer b) override {
        const int i = index(b);
        EXPECT_TRUE(locked.count(i)) << "released twice or never locked: " << i;
        EXPECT_NE(i, onScreen) << "released while scanned out";
        locked.erase(i);
        calls.push_back("release " + std::to_string(i));
    }
    std::uint32_t framebufferFor(Buffer b) override { return std::uint32_t(100 + index(b)); }
    bool setMode(std::uint32_t fb) override {
        calls.push_back("modeset " + std::to_string(fb));
        if (!connected) return false;
        onScreen = int(fb) - 100;
        return true;
    }
    bool pageFlip(std::uint32_t fb) override {
        calls.push_back("flip " + std::to_string(fb));
        EXPECT_EQ(queued, -1) << "a second flip queued behind a pending one";
        if (flipFails || !connected) return false;
        queued = int(fb) - 100;
        return true;
    }
    Wait waitForFlip(int timeoutMs) override {
        EXPECT_GT(timeoutMs, 0);
        calls.push_back("wait");
        if (vblankStops || queued < 0) {
            ++waitsTimedOut;
            return Wait::Timeout;
        }
        onScreen = queued;  // vblank: the queued buffer is now scanned out
        queued = -1;
        return Wait::Flipped;
    }
    bool connectorConnected() override { return connected; }

    static Buffer id(int i) { return reinterpret_cast<Buffer>(std::uintptr_t(i + 1)); }
    static int index(Buffer b) { return int(reinterpret_cast<std::uintptr_t>(b)) - 1; }
    int count(const std::string& prefix) const {
        return int(std::count_if(calls.begin(), calls.end(),
                                 [&](const std::string& c) { return c.rfind(prefix, 0) == 0; }));
    }
};

/** @brief As KmsDisplay's destructor: settle, give the CRTC back, release the buffers. */
void teardown(FakeKms& dev, KmsFlipLoop& loop) {
    loop.settle();
    EXPECT_EQ(dev.queued, -1);
    dev.onScreen = -1;  // CRTC restored to the console
    loop.releaseAll();
}

TEST(KmsFlipLoopTest, ModeSetOnceThenOneFlipPerFrameWithVblankWait) {
    FakeKms dev;
    KmsFlipLoop loop(dev, 1000);
    for (int frame = 0; frame < 10; ++frame) ASSERT_TRUE(loop.present()) << loop.error();
    EXPECT_EQ(dev.count("modeset"), 1);
    EXPECT_EQ(dev.calls[1], "modeset 100");
    EXPECT_EQ(dev.count("flip"), 9);
    EXPECT_EQ(loop.flips(), 9u);
    EXPECT_EQ(dev.count("wait"), 9);  // each flip waited for before the next frame
    // Each frame's buffer is released once the next one is on screen: at most 1 locked after a
    // frame (the one scanned out), so rendering never runs out of buffers.
    EXPECT_EQ(dev.locked.size(), 1u);
    EXPECT_EQ(loop.buffersReleased(), 9u);
    teardown(dev, loop);
    EXPECT_TRUE(dev.locked.empty());
}

TEST(KmsFlipLoopTest, HungVblankTimesOutWithoutQueueingASecondFlip) {
    FakeKms dev;
    KmsFlipLoop loop(dev, 50);
    ASSERT_TRUE(loop.present());
    ASSERT_TRUE(loop.present());
    dev.vblankStops = true;
    EXPECT_FALSE(loop.present());
    EXPECT_NE(loop.error().find("did not complete within 50 ms"), std::string::npos)
        << loop.error();
    EXPECT_FALSE(loop.unplugged());
    // Next frame: the old flip is still pending; no new flip is queued behind it.
    const int flips = dev.count("flip");
    EXPECT_FALSE(loop.present());
    EXPECT_EQ(dev.count("flip"), flips);
    // The display recovers: the pending flip lands, frames flow again.
    dev.vblankStops = false;
    EXPECT_TRUE(loop.present()) << loop.error();
    EXPECT_TRUE(loop.present()) << loop.error();
    teardown(dev, loop);
    EXPECT_TRUE(dev.locked.empty());
}

TEST(KmsFlipLoopTest, ConnectorUnplugIsReportedAndBuffersReturned) {
    FakeKms dev;
    KmsFlipLoop loop(dev, 1000);
    ASSERT_TRUE(loop.present());
    ASSERT_TRUE(loop.present());
    dev.connected = false;  // hot-unplug: the kernel refuses the flip
    EXPECT_FALSE(loop.present());
    EXPECT_TRUE(loop.unplugged());
    EXPECT_NE(loop.error().find("unplugged"), std::string::npos) << loop.error();
    EXPECT_EQ(dev.locked.size(), 1u);  // only the buffer still scanned out
    teardown(dev, loop);
    EXPECT_TRUE(dev.locked.empty());
}

TEST(KmsFlipLoopTest, FailedFlipOnAConnectedDisplayIsNotAnUnplug) {
    FakeKms dev;
    KmsFlipLoop loop(dev, 1000);
    ASSERT_TRUE(loop.present());
    dev.flipFails = true;
    EXPECT_FALSE(loop.present());
    EXPECT_FALSE(loop.unplugged());
    EXPECT_EQ(loop.error(), "page flip failed");
    dev.flipFails = false;
    EXPECT_TRUE(loop.present());
}

TEST(KmsFlipLoopTest, ModeSetFailureReleasesTheBuffer) {
    FakeKms dev;
    dev.connected = false;
    KmsFlipLoop loop(dev, 1000);
    EXPECT_FALSE(loop.present());
    EXPECT_FALSE(loop.modeSet());
    EXPECT_TRUE(loop.unplugged());
    EXPECT_TRUE(dev.locked.empty());
}

}  // namespace
}  // namespace kiosk::platform
