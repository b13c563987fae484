#include "runtime/loader/TileLoader.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace kiosk::loader {
namespace {

using namespace std::chrono_literals;
using terrain::TileKey;
using terrain::TilePayload;

TileKey key(int n) {
    return TileKey{0, 0, TileId{8, n, 0}};
}

/**
 * @brief Records the order of loads; the load of `gateKey` blocks until open() so tests can
 * queue work behind it deterministically.
 */
struct Recorder {
    std::mutex m;
    std::condition_variable cv;
    std::vector<TileKey> order;
    bool gateOpen = false;
    bool inGate = false;
    bool started = false, stopping = false;
    int delayUs = 0;

    void open() {
        std::lock_guard<std::mutex> l(m);
        gateOpen = true;
        cv.notify_all();
    }
    void waitInGate() {
        std::unique_lock<std::mutex> l(m);
        ASSERT_TRUE(cv.wait_for(l, 5s, [&] { return inGate; }));
    }
    std::vector<TileKey> snapshot() {
        std::lock_guard<std::mutex> l(m);
        return order;
    }
};

class RecordingLoad final : public LoadFunction {
public:
    RecordingLoad(Recorder& r, TileKey gate, bool throwOn = false)
        : mR(r), mGate(gate), mThrow(throwOn) {}
    void threadStarted() override {
        std::lock_guard<std::mutex> l(mR.m);
        mR.started = true;
    }
    void threadStopping() override {
        std::lock_guard<std::mutex> l(mR.m);
        mR.stopping = true;
    }
    TilePayload load(const LoadRequest& req) override {
        {
            std::unique_lock<std::mutex> l(mR.m);
            mR.order.push_back(req.key);
            if (req.key == mGate) {
                mR.inGate = true;
                mR.cv.notify_all();
                mR.cv.wait(l, [&] { return mR.gateOpen; });
            }
        }
        if (mR.delayUs) std::this_thread::sleep_for(std::chrono::microseconds(mR.delayUs));
        if (mThrow && req.key.id.column == 13) throw std::runtime_error("boom");
        TilePayload p;
        p.raster = io::RasterTile{};
        p.raster->values.assign(16, float(req.key.id.column));
        return p;
    }

private:
    Recorder& mR;
    TileKey mGate;
    bool mThrow;
};

// Pops until `count` results arrived (or a timeout), checking each key at most once.
std::vector<LoadResult> drain(TileLoader& loader, std::size_t count,
                              std::chrono::milliseconds timeout = 5000ms) {
    std::vector<LoadResult> out;
    const auto end = std::chrono::steady_clock::now() + timeout;
    LoadResult r;
    while (out.size() < count && std::chrono::steady_clock::now() < end) {
        if (loader.tryPop(r))
            out.push_back(std::move(r));
        else
            std::this_thread::sleep_for(200us);
    }
    return out;
}

TEST(TileLoader, HighestPriorityFirst) {
    Recorder rec;
    TileLoader loader(LoaderOptions{32, 64}, std::make_unique<RecordingLoad>(rec, key(100)));
    loader.request(key(100), 1.0);
    loader.submit();
    rec.waitInGate();
    const double prio[] = {3, 9, 1, 7, 5, 8, 2, 6, 4, 0.5};
    for (int i = 0; i < 10; ++i) loader.request(key(i), prio[i]);
    loader.submit();
    rec.open();
    const auto results = drain(loader, 11);
    ASSERT_EQ(results.size(), 11u);
    const auto order = rec.snapshot();
    ASSERT_EQ(order.size(), 11u);
    for (std::size_t i = 2; i < order.size(); ++i)
        EXPECT_GT(prio[order[i - 1].id.column], prio[order[i].id.column]) << "position " << i;
    EXPECT_EQ(order[1], key(1));  // priority 9
    for (const auto& r : results) {
        ASSERT_TRUE(r.payload.raster.has_value());
        EXPECT_EQ(r.payload.key, r.request.key);
        EXPECT_EQ(r.payload.raster->values[0], float(r.request.key.id.column));
    }
}

TEST(TileLoader, SubmitVectorAppendsToThisFramesRequests) {
    Recorder rec;
    rec.gateOpen = true;
    TileLoader loader(LoaderOptions{8, 16}, std::make_unique<RecordingLoad>(rec, key(-1)));
    loader.request(key(1), 1.0);
    loader.submit({terrain::TileRequest{key(2), 5.0}, terrain::TileRequest{key(3), 3.0}});
    const auto results = drain(loader, 3);
    ASSERT_EQ(results.size(), 3u);
    EXPECT_EQ(loader.counters().submitted, 3u);
    std::set<int> got;
    for (const auto& r : results) got.insert(r.request.key.id.column);
    EXPECT_EQ(got, (std::set<int>{1, 2, 3}));
}

TEST(TileLoader, NewSubmissionDropsStaleRequests) {
    Recorder rec;
    TileLoader loader(LoaderOptions{32, 64}, std::make_unique<RecordingLoad>(rec, key(100)));
    loader.request(key(100), 1.0);
    loader.submit();
    rec.waitInGate();
    for (int i = 0; i < 3; ++i) loader.request(key(i), 10.0);
    loader.submit();
    const std::uint64_t g1 = loader.generation();
    loader.request(key(7), 1.0);
    loader.request(key(8), 2.0);
    loader.submit();
    EXPECT_EQ(loader.generation(), g1 + 1);
    rec.open();
    const auto results = drain(loader, 3);
    ASSERT_EQ(results.size(), 3u);
    EXPECT_EQ(rec.snapshot(), (std::vector<TileKey>{key(100), key(8), key(7)}));
    EXPECT_EQ(results[1].request.generation, loader.generation());
    LoadResult extra;
    std::this_thread::sleep_for(20ms);
    EXPECT_FALSE(loader.tryPop(extra));
    EXPECT_GE(loader.counters().droppedStale, 3u);
}

TEST(TileLoader, EachKeyLoadedAndDeliveredOnce) {
    Recorder rec;
    rec.gateOpen = true;
    rec.delayUs = 300;
    TileLoader loader(LoaderOptions{4, 64}, std::make_unique<RecordingLoad>(rec, key(-1)));
    std::map<int, int> delivered;
    LoadResult r;
    // Frames keep re-requesting everything not yet delivered (as the selector would).
    for (int frame = 0; frame < 2000 && delivered.size() < 40; ++frame) {
        for (int i = 0; i < 40; ++i)
            if (!delivered.count(i)) loader.request(key(i), double(i % 7));
        loader.submit();
        while (loader.tryPop(r)) ++delivered[r.request.key.id.column];
        std::this_thread::sleep_for(200us);
    }
    ASSERT_EQ(delivered.size(), 40u);
    for (const auto& [k, n] : delivered) EXPECT_EQ(n, 1) << "key " << k;
    std::map<int, int> loads;
    for (const TileKey& k : rec.snapshot()) ++loads[k.id.column];
    for (const auto& [k, n] : loads) EXPECT_EQ(n, 1) << "key " << k << " loaded twice";
    EXPECT_EQ(loader.counters().delivered, 40u);
}

TEST(TileLoader, InFlightCapHoldsUntilResultsAreTaken) {
    Recorder rec;
    rec.gateOpen = true;
    TileLoader loader(LoaderOptions{2, 16}, std::make_unique<RecordingLoad>(rec, key(-1)));
    for (int i = 0; i < 10; ++i) loader.request(key(i), double(10 - i));
    loader.submit();
    const auto end = std::chrono::steady_clock::now() + 5s;
    while (loader.inFlight() < 2 && std::chrono::steady_clock::now() < end)
        std::this_thread::sleep_for(1ms);
    std::this_thread::sleep_for(30ms);
    EXPECT_EQ(loader.inFlight(), 2u);
    EXPECT_EQ(rec.snapshot().size(), 2u);
    LoadResult r;
    ASSERT_TRUE(loader.tryPop(r));
    EXPECT_EQ(r.request.key, key(0));
    const auto more = drain(loader, 9);
    EXPECT_EQ(more.size(), 9u);
    EXPECT_EQ(rec.snapshot().size(), 10u);
}

TEST(TileLoader, PrefetchOnlyWhenFrameQueueIsEmpty) {
    Recorder rec;
    TileLoader loader(LoaderOptions{32, 64}, std::make_unique<RecordingLoad>(rec, key(100)));
    loader.request(key(100), 1.0);
    loader.submit();
    rec.waitInGate();
    loader.prefetch({terrain::TileRequest{key(50), 1000.0}, terrain::TileRequest{key(51), 2000.0}});
    loader.request(key(1), 1.0);
    loader.request(key(2), 2.0);
    loader.submit();
    rec.open();
    const auto results = drain(loader, 5);
    ASSERT_EQ(results.size(), 5u);
    EXPECT_EQ(rec.snapshot(), (std::vector<TileKey>{key(100), key(2), key(1), key(51), key(50)}));
    EXPECT_TRUE(results[3].request.prefetch);
    EXPECT_FALSE(results[1].request.prefetch);
}

// Scrubbing (issue 6): the scene sends the prefetch plan of the new playhead; the queued
// requests of the old one are dropped without being loaded.
TEST(TileLoader, NewPrefetchSetDropsTheOldOne) {
    Recorder rec;
    TileLoader loader(LoaderOptions{32, 64}, std::make_unique<RecordingLoad>(rec, key(100)));
    loader.request(key(100), 1.0);
    loader.submit();
    rec.waitInGate();
    loader.prefetch({terrain::TileRequest{key(50), 1000.0}, terrain::TileRequest{key(51), 2000.0}});
    loader.prefetch({terrain::TileRequest{key(60), 1.0}});
    rec.open();
    const auto results = drain(loader, 2);
    ASSERT_EQ(results.size(), 2u);
    LoadResult extra;
    std::this_thread::sleep_for(20ms);
    EXPECT_FALSE(loader.tryPop(extra));
    EXPECT_EQ(rec.snapshot(), (std::vector<TileKey>{key(100), key(60)}));
    EXPECT_GE(loader.counters().droppedStale, 2u);
}

// The scene's load-time estimate (prefetch depth) comes from the loader's own measurement.
TEST(TileLoader, ResultsCarryTheirLoadTime) {
    Recorder rec;
    rec.delayUs = 3000;
    TileLoader loader(LoaderOptions{32, 64}, std::make_unique<RecordingLoad>(rec, key(100)));
    loader.request(key(1), 1.0);
    loader.submit();
    const auto results = drain(loader, 1);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_GE(results[0].loadSeconds, 0.003);
    EXPECT_LT(results[0].loadSeconds, 2.0);
}

TEST(TileLoader, InvalidateDiscardsWorkStartedBefore) {
    Recorder rec;
    TileLoader loader(LoaderOptions{32, 64}, std::make_unique<RecordingLoad>(rec, key(100)));
    loader.request(key(100), 1.0);
    loader.request(key(5), 0.5);
    loader.submit();
    rec.waitInGate();
    loader.invalidate();
    loader.request(key(6), 1.0);
    loader.submit();
    rec.open();
    const auto results = drain(loader, 1);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_EQ(results[0].request.key, key(6));
    std::this_thread::sleep_for(20ms);
    LoadResult r;
    EXPECT_FALSE(loader.tryPop(r));
    EXPECT_EQ(loader.counters().droppedInvalidated, 1u);
}

TEST(TileLoader, ExceptionBecomesFailedPayload) {
    Recorder rec;
    rec.gateOpen = true;
    TileLoader loader(LoaderOptions{4, 16}, std::make_unique<RecordingLoad>(rec, key(-1), true));
    loader.request(key(13), 1.0);
    loader.submit();
    const auto results = drain(loader, 1);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_EQ(results[0].payload.status, TilePayload::Status::Failed);
    const Diagnostic* d = results[0].payload.diagnostics.firstError();
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->code, "LOADER_EXCEPTION");
    EXPECT_EQ(d->where, "layer 0 frame 0 tile 8/13/0");
    EXPECT_EQ(d->message, "boom");
}

TEST(TileLoader, TryPopOnEmptyReturnsImmediately) {
    Recorder rec;
    TileLoader loader(LoaderOptions{4, 16}, std::make_unique<RecordingLoad>(rec, key(100)));
    loader.request(key(100), 1.0);  // the loader thread is busy (blocked) meanwhile
    loader.submit();
    rec.waitInGate();
    LoadResult r;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 1000; ++i) ASSERT_FALSE(loader.tryPop(r));
    const auto dt = std::chrono::steady_clock::now() - t0;
    EXPECT_LT(dt, 200ms);  // 1000 calls; a single blocking wait would be unbounded
    rec.open();
}

TEST(TileLoader, ShutdownJoinsWithPendingWork) {
    Recorder rec;
    rec.gateOpen = true;
    rec.delayUs = 2000;
    const auto t0 = std::chrono::steady_clock::now();
    {
        TileLoader loader(LoaderOptions{1000, 1000}, std::make_unique<RecordingLoad>(rec, key(-1)));
        for (int i = 0; i < 1000; ++i) loader.request(key(i), double(i));
        loader.submit();
        std::this_thread::sleep_for(10ms);
    }  // destructor: drop pending, finish the current load, join
    const auto dt = std::chrono::steady_clock::now() - t0;
    EXPECT_LT(dt, 1500ms);
    EXPECT_LT(rec.snapshot().size(), 1000u);
    EXPECT_TRUE(rec.started);
    EXPECT_TRUE(rec.stopping);
}

// The completion ring bounded by bytes (LoaderOptions::maxBytesInFlight, issue 14): however far
// the render thread falls behind, decoded-but-not-taken payloads stay under the bound plus one.

/** @brief Every tile decodes to a raster of `floats` values; counts its loads. */
class SizedLoad final : public LoadFunction {
public:
    SizedLoad(std::size_t floats, std::atomic<int>& loads) : mFloats(floats), mLoads(loads) {}
    TilePayload load(const LoadRequest&) override {
        ++mLoads;
        TilePayload p;
        p.raster = io::RasterTile{};
        p.raster->values.assign(mFloats, 1.0f);
        return p;
    }

private:
    std::size_t mFloats;
    std::atomic<int>& mLoads;
};

constexpr std::size_t kMiB = std::size_t(1) << 20;

// Waits until `loads` stops moving (the loader idles on its bound) and returns it.
int settledLoads(const std::atomic<int>& loads) {
    int last = -1;
    for (int i = 0; i < 100 && loads.load() != last; ++i) {
        last = loads.load();
        std::this_thread::sleep_for(30ms);
    }
    return loads.load();
}

TEST(TileLoaderBytes, RingStopsAtTheByteBoundNotTheCount) {
    std::atomic<int> loads{0};
    LoaderOptions o;
    o.maxInFlight = 8;
    o.maxBytesInFlight = 2 * kMiB;
    TileLoader loader(o, std::make_unique<SizedLoad>(kMiB / sizeof(float), loads));  // 1 MiB each
    for (int i = 0; i < 10; ++i) loader.request(key(i), double(10 - i));
    loader.submit();
    // Two 1 MiB payloads (plus their headers) reach 2 MiB: no third load while nothing is taken.
    EXPECT_EQ(settledLoads(loads), 2);
    EXPECT_EQ(loader.inFlight(), 2u);
    EXPECT_GE(loader.heldBytes(), 2 * kMiB);
    EXPECT_GT(loader.counters().waitsForBytes, 0u);
    // Taking one makes room for one more.
    LoadResult r;
    ASSERT_TRUE(loader.tryPop(r));
    EXPECT_EQ(settledLoads(loads), 3);
    // Drain the rest: every request is still served, one bound's worth at a time.
    int taken = 1;
    const auto end = std::chrono::steady_clock::now() + 5s;
    while (taken < 10 && std::chrono::steady_clock::now() < end) {
        if (loader.tryPop(r))
            ++taken;
        else
            std::this_thread::sleep_for(1ms);
    }
    EXPECT_EQ(taken, 10);
    EXPECT_EQ(loader.heldBytes(), 0u);
    // Never more than the bound plus one payload.
    EXPECT_LE(loader.counters().heldBytesHigh, 3 * kMiB);
}

TEST(TileLoaderBytes, APayloadLargerThanTheBoundStillGoesThrough) {
    std::atomic<int> loads{0};
    LoaderOptions o;
    o.maxInFlight = 8;
    o.maxBytesInFlight = kMiB / 2;
    TileLoader loader(o, std::make_unique<SizedLoad>(kMiB / sizeof(float), loads));
    for (int i = 0; i < 3; ++i) loader.request(key(i), double(3 - i));
    loader.submit();
    EXPECT_EQ(settledLoads(loads), 1);  // one result at a time, never none
    LoadResult r;
    for (int taken = 0; taken < 3; ++taken) {
        const auto end = std::chrono::steady_clock::now() + 5s;
        bool got = false;
        while (!got && std::chrono::steady_clock::now() < end) {
            got = loader.tryPop(r);
            if (!got) std::this_thread::sleep_for(1ms);
        }
        ASSERT_TRUE(got) << "result " << taken;
        EXPECT_EQ(r.payload.raster->values.size(), kMiB / sizeof(float));
    }
}

TEST(TileLoaderBytes, ZeroMeansCountOnly) {
    std::atomic<int> loads{0};
    LoaderOptions o;
    o.maxInFlight = 4;
    o.maxBytesInFlight = 0;
    TileLoader loader(o, std::make_unique<SizedLoad>(kMiB / sizeof(float), loads));
    for (int i = 0; i < 10; ++i) loader.request(key(i), double(10 - i));
    loader.submit();
    EXPECT_EQ(settledLoads(loads), 4);
    EXPECT_EQ(loader.counters().waitsForBytes, 0u);
}

}  // namespace
}  // namespace kiosk::loader
