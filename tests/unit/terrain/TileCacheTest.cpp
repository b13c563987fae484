#include "runtime/terrain/TileCache.h"
#include "runtime/terrain/TilePayload.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>
#include <vector>

namespace kiosk::terrain {
namespace {

TileKey key(int n, std::uint16_t layer = 0) {
    return TileKey{layer, 0, TileId{10, n, n / 7}};
}

using Cache = TileCache<std::string>;

TEST(TileCache, LruOrderAndEvictionOfLeastRecentlyUsed) {
    Cache cache(CacheBudget{300, 1000}, 16);
    cache.beginFrame(1);
    const TileHandle a = cache.insert(key(1), "a", 100);
    const TileHandle b = cache.insert(key(2), "b", 100);
    const TileHandle c = cache.insert(key(3), "c", 100);
    ASSERT_TRUE(a.valid() && b.valid() && c.valid());
    EXPECT_EQ(cache.lruOrder(), (std::vector<TileKey>{key(3), key(2), key(1)}));

    cache.beginFrame(2);
    EXPECT_EQ(cache.acquire(key(1)), a);
    EXPECT_EQ(cache.lruOrder(), (std::vector<TileKey>{key(1), key(3), key(2)}));
    EXPECT_FALSE(cache.find(key(4)).valid());

    // Full: inserting d evicts the least recently used unpinned entry, b.
    const TileHandle d = cache.insert(key(4), "d", 100);
    ASSERT_TRUE(d.valid());
    EXPECT_EQ(cache.get(b), nullptr);
    EXPECT_FALSE(cache.find(key(2)).valid());
    ASSERT_EQ(cache.evicted().size(), 1u);
    EXPECT_EQ(cache.evicted()[0].key, key(2));
    EXPECT_EQ(cache.evicted()[0].handle, b);
    EXPECT_EQ(*cache.get(a), "a");
    EXPECT_EQ(*cache.get(c), "c");
    EXPECT_EQ(cache.cpuBytes(), 300u);
    cache.clearEvicted();
    EXPECT_TRUE(cache.evicted().empty());
}

TEST(TileCache, PinnedEntriesAreNeverEvicted) {
    Cache cache(CacheBudget{300, 300}, 16);
    cache.beginFrame(1);
    cache.insert(key(1), "a", 100);
    cache.insert(key(2), "b", 100);
    cache.beginFrame(2);
    const TileHandle a = cache.acquire(key(1));  // used this frame
    const TileHandle c = cache.insert(key(3), "c", 100);
    EXPECT_TRUE(cache.isPinned(a));
    EXPECT_TRUE(cache.isPinned(c));
    // Needs 200 bytes: only b (100, unpinned) can go, so it is refused and nothing changes.
    EXPECT_FALSE(cache.insert(key(4), "big", 200).valid());
    EXPECT_TRUE(cache.find(key(2)).valid());
    EXPECT_TRUE(cache.evicted().empty());
    EXPECT_EQ(cache.size(), 3u);
    // GPU reservation follows the same rule.
    EXPECT_TRUE(cache.reserveGpu(a, 250));
    EXPECT_FALSE(cache.reserveGpu(c, 100));
    EXPECT_EQ(cache.gpuBytes(), 250u);
    // Next frame nothing is pinned: the reservation for c evicts a (LRU with GPU bytes).
    cache.beginFrame(3);
    cache.touch(c);
    EXPECT_TRUE(cache.reserveGpu(c, 100));
    EXPECT_FALSE(cache.contains(a));
    EXPECT_EQ(cache.gpuBytes(), 100u);
}

TEST(TileCache, StaleHandlesAreDetectedAfterSlotReuse) {
    Cache cache(CacheBudget{1000, 1000}, 2);
    cache.beginFrame(1);
    const TileHandle a = cache.insert(key(1), "a", 10);
    ASSERT_TRUE(cache.erase(a));
    EXPECT_EQ(cache.get(a), nullptr);
    EXPECT_FALSE(cache.erase(a));
    const TileHandle b = cache.insert(key(2), "b", 10);
    const TileHandle c = cache.insert(key(3), "c", 10);
    EXPECT_TRUE(b.index() == a.index() || c.index() == a.index());  // the slot came back
    EXPECT_NE(b, a);
    EXPECT_NE(c, a);
    EXPECT_EQ(cache.get(a), nullptr);
    EXPECT_FALSE(cache.touch(a));
    EXPECT_FALSE(cache.reserveGpu(a, 1));
    // Slots exhausted: the next insert evicts LRU (b) even though bytes would fit.
    cache.beginFrame(2);
    const TileHandle d = cache.insert(key(4), "d", 10);
    ASSERT_TRUE(d.valid());
    EXPECT_EQ(cache.get(b), nullptr);
    // Replacing a key invalidates the old handle.
    const TileHandle c2 = cache.insert(key(3), "c2", 10);
    EXPECT_EQ(cache.get(c), nullptr);
    EXPECT_EQ(*cache.get(c2), "c2");
}

TEST(TileCache, BudgetNeverExceededUnderRandomWorkload) {
    const CacheBudget budget{50000, 30000};
    Cache cache(budget, 256);
    std::mt19937 rng(1234);
    std::map<std::uint64_t, TileHandle> live;  // our view: key -> handle
    std::uint64_t frame = 0;
    std::size_t refused = 0, inserted = 0;
    for (int op = 0; op < 20000; ++op) {
        const int kind = int(rng() % 10);
        const TileKey k = key(int(rng() % 400), std::uint16_t(rng() % 3));
        if (kind == 0) {
            cache.beginFrame(++frame);
        } else if (kind <= 4) {
            const std::size_t bytes = 100 + rng() % 3000;
            const TileHandle h = cache.insert(k, std::to_string(op), bytes);
            if (h.valid())
                ++inserted;
            else
                ++refused;
        } else if (kind <= 6) {
            cache.acquire(k);
        } else if (kind <= 8) {
            const TileHandle h = cache.find(k);
            if (h.valid()) cache.reserveGpu(h, 500 + rng() % 4000);
        } else {
            const TileHandle h = cache.find(k);
            if (h.valid()) cache.setCpuBytes(h, rng() % 2000);
        }
        ASSERT_LE(cache.cpuBytes(), budget.cpuBytes) << "op " << op;
        ASSERT_LE(cache.gpuBytes(), budget.gpuBytes) << "op " << op;
        ASSERT_LE(cache.size(), 256u);
        // Evicted handles must be stale.
        for (const auto& e : cache.evicted()) ASSERT_EQ(cache.get(e.handle), nullptr);
        cache.clearEvicted();
    }
    EXPECT_GT(inserted, 1000u);
    // Accounting matches the entries that remain.
    std::size_t gpu = 0;
    for (int n = 0; n < 400; ++n)
        for (std::uint16_t l = 0; l < 3; ++l) gpu += cache.gpuBytesOf(cache.find(key(n, l)));
    EXPECT_EQ(gpu, cache.gpuBytes());
    (void)refused;
}

TEST(TileCache, SetBudgetShrinksButKeepsPinned) {
    Cache cache(CacheBudget{1000, 1000}, 16);
    cache.beginFrame(1);
    for (int i = 0; i < 5; ++i) cache.insert(key(i), "x", 100);
    cache.beginFrame(2);
    cache.acquire(key(0));
    cache.setBudget(CacheBudget{250, 1000});
    EXPECT_LE(cache.cpuBytes(), 250u);
    EXPECT_TRUE(cache.find(key(0)).valid());
    EXPECT_TRUE(cache.find(key(4)).valid());  // most recent unpinned stays
    EXPECT_EQ(cache.evicted().size(), 3u);
}

TEST(CacheResidency, DrawableNeedsGpuUnlessAbsent) {
    TerrainTileCache cache(CacheBudget{1 << 20, 1 << 20}, 8);
    cache.beginFrame(1);
    TilePayload ready;
    ready.mesh = TileMesh{};
    const TileHandle h = cache.insert(key(1), std::move(ready), 100);
    TilePayload absent;
    absent.status = TilePayload::Status::Absent;
    const TileHandle ha = cache.insert(key(2), std::move(absent), 10);
    CacheResidency gpu(cache, true), cpu(cache, false);
    EXPECT_FALSE(gpu.drawable(key(1)).valid());
    EXPECT_EQ(cpu.drawable(key(1)), h);
    EXPECT_EQ(gpu.drawable(key(2)), ha);
    ASSERT_TRUE(cache.reserveGpu(h, 64));
    EXPECT_EQ(gpu.drawable(key(1)), h);
    EXPECT_FALSE(gpu.drawable(key(3)).valid());
    cache.beginFrame(2);
    CacheResidency lookAhead(cache, true, /*pin=*/false);
    EXPECT_EQ(lookAhead.drawable(key(1)), h);
    EXPECT_FALSE(cache.isPinned(h));
    gpu.drawable(key(1));
    EXPECT_TRUE(cache.isPinned(h));
    EXPECT_FALSE(cache.isPinned(ha));
}

}  // namespace
}  // namespace kiosk::terrain
