#pragma once

#include "runtime/terrain/TileKey.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace kiosk::terrain {

/** @brief Residency limits in bytes: CPU payloads and, separately, what the renderer uploaded. */
struct CacheBudget {
    std::size_t cpuBytes = std::size_t(256) << 20;
    std::size_t gpuBytes = std::size_t(256) << 20;
};

/**
 * @brief LRU cache of tile payloads with byte budgets and generation-checked slot handles.
 *
 * Contract:
 * - cpuBytes() <= budget().cpuBytes and gpuBytes() <= budget().gpuBytes at all times: insert()
 *   and reserveGpu() evict least-recently-used entries to make room and refuse (invalid handle /
 *   false) when that is impossible, leaving the cache unchanged.
 * - An entry used (acquire/touch/insert) during the current frame (beginFrame) is pinned and is
 *   never evicted in that frame, so handles the selector returned stay valid until drawn.
 * - Handles carry the slot generation; once an entry is evicted or erased, get() on an old
 *   handle returns nullptr even if the slot was reused (sokol's dangling-access check).
 * - Evicted entries are listed in evicted() (key, handle, GPU bytes) until clearEvicted(): the
 *   renderer frees its GL objects for those slots (it may index its own arrays by
 *   handle.index() < capacity()).
 *
 * Threads: render thread only. Slots and the hash index are sized at construction; nothing
 * allocates afterwards except the payloads themselves (and evicted() beyond `maxSlots` entries).
 */
template <class T>
class TileCache {
public:
    explicit TileCache(CacheBudget budget, std::uint32_t maxSlots = 4096)
        : mBudget(budget),
          mSlots(std::min<std::uint32_t>(std::max<std::uint32_t>(maxSlots, 1),
                                         TileHandle::kIndexMask)) {
        std::size_t tableSize = 16;
        while (tableSize < std::size_t(mSlots.size()) * 2) tableSize *= 2;
        mTable.assign(tableSize, kNil);
        mFree.reserve(mSlots.size());
        for (std::uint32_t i = std::uint32_t(mSlots.size()); i-- > 0;) mFree.push_back(i);
        mEvicted.reserve(mSlots.size());
    }

    struct Evicted {
        TileKey key;
        TileHandle handle;
        std::size_t gpuBytes = 0;
    };

    /** @brief Start a frame: entries used from now on are pinned until the next beginFrame. */
    void beginFrame(std::uint64_t frame) { mFrame = frame; }
    std::uint64_t frame() const noexcept { return mFrame; }

    /** @brief Handle for key, without touching LRU order; invalid if not cached. */
    TileHandle find(const TileKey& key) const {
        const std::uint32_t s = lookup(key);
        return s == kNil ? TileHandle{} : makeHandle(s);
    }
    /** @brief find() + touch(): marks the entry most recently used and pins it this frame. */
    TileHandle acquire(const TileKey& key) {
        const TileHandle h = find(key);
        if (h.valid()) touch(h);
        return h;
    }
    bool touch(TileHandle h) {
        const std::uint32_t s = resolve(h);
        if (s == kNil) return false;
        mSlots[s].lastUsed = mFrame;
        unlink(s);
        pushFront(s);
        return true;
    }
    bool contains(TileHandle h) const { return resolve(h) != kNil; }
    bool isPinned(TileHandle h) const {
        const std::uint32_t s = resolve(h);
        return s != kNil && mSlots[s].lastUsed == mFrame;
    }
    T* get(TileHandle h) {
        const std::uint32_t s = resolve(h);
        return s == kNil ? nullptr : mSlots[s].payload.get();
    }
    const T* get(TileHandle h) const {
        const std::uint32_t s = resolve(h);
        return s == kNil ? nullptr : mSlots[s].payload.get();
    }
    const TileKey* keyOf(TileHandle h) const {
        const std::uint32_t s = resolve(h);
        return s == kNil ? nullptr : &mSlots[s].key;
    }
    std::size_t gpuBytesOf(TileHandle h) const {
        const std::uint32_t s = resolve(h);
        return s == kNil ? 0 : mSlots[s].gpuBytes;
    }

    /**
     * @brief Insert (or replace) key's payload costing `cpuBytes`; pinned for this frame.
     * Returns an invalid handle, dropping the payload, if it cannot fit without evicting
     * pinned entries. Replacing an entry first removes the old one (its handle goes stale and
     * it is listed in evicted()), even if the new payload then does not fit.
     */
    TileHandle insert(const TileKey& key, T&& payload, std::size_t cpuBytes) {
        const std::uint32_t existing = lookup(key);
        if (existing != kNil) evictSlot(existing);
        if (cpuBytes > mBudget.cpuBytes) return {};
        if (!makeRoom(cpuBytes, 0, kNil, mFree.empty() ? 1 : 0)) return {};
        const std::uint32_t s = mFree.back();
        mFree.pop_back();
        Slot& slot = mSlots[s];
        slot.payload = std::make_unique<T>(std::move(payload));
        slot.key = key;
        slot.cpuBytes = cpuBytes;
        slot.gpuBytes = 0;
        slot.lastUsed = mFrame;
        slot.used = true;
        mCpu += cpuBytes;
        tableInsert(s);
        pushFront(s);
        ++mCount;
        return makeHandle(s);
    }

    /**
     * @brief Set the GPU bytes of an entry before uploading it (replaces its previous value),
     * evicting other unpinned entries as needed. False: it does not fit, do not upload.
     */
    bool reserveGpu(TileHandle h, std::size_t gpuBytes) {
        const std::uint32_t s = resolve(h);
        if (s == kNil || gpuBytes > mBudget.gpuBytes) return false;
        const std::size_t current = mSlots[s].gpuBytes;
        if (gpuBytes > current && !makeRoom(0, gpuBytes - current, s, 0)) return false;
        mGpu = mGpu - current + gpuBytes;
        mSlots[s].gpuBytes = gpuBytes;
        return true;
    }
    /** @brief Lower (or raise, if it fits) an entry's CPU bytes, e.g. after dropping vertices. */
    bool setCpuBytes(TileHandle h, std::size_t cpuBytes) {
        const std::uint32_t s = resolve(h);
        if (s == kNil || cpuBytes > mBudget.cpuBytes) return false;
        const std::size_t current = mSlots[s].cpuBytes;
        if (cpuBytes > current && !makeRoom(cpuBytes - current, 0, s, 0)) return false;
        mCpu = mCpu - current + cpuBytes;
        mSlots[s].cpuBytes = cpuBytes;
        return true;
    }
    bool erase(TileHandle h) {
        const std::uint32_t s = resolve(h);
        if (s == kNil) return false;
        evictSlot(s);
        return true;
    }
    /** @brief New limits; evicts unpinned LRU entries until they hold (pinned ones may not). */
    void setBudget(CacheBudget budget) {
        mBudget = budget;
        std::uint32_t s = mTail;
        while (s != kNil && (mCpu > mBudget.cpuBytes || mGpu > mBudget.gpuBytes)) {
            const std::uint32_t prev = mSlots[s].prev;
            if (mSlots[s].lastUsed != mFrame) evictSlot(s);
            s = prev;
        }
    }

    const CacheBudget& budget() const noexcept { return mBudget; }
    /**
     * @brief CPU and GPU bytes of the entries pinned this frame: the working set of what was
     * used since beginFrame(). Pinned entries lead the LRU list, so this walks only them.
     */
    std::pair<std::size_t, std::size_t> pinnedBytes() const {
        std::size_t cpu = 0, gpu = 0;
        for (std::uint32_t s = mHead; s != kNil && mSlots[s].lastUsed == mFrame;
             s = mSlots[s].next) {
            cpu += mSlots[s].cpuBytes;
            gpu += mSlots[s].gpuBytes;
        }
        return {cpu, gpu};
    }
    std::size_t cpuBytes() const noexcept { return mCpu; }
    std::size_t gpuBytes() const noexcept { return mGpu; }
    std::size_t size() const noexcept { return mCount; }
    std::uint32_t capacity() const noexcept { return std::uint32_t(mSlots.size()); }
    const std::vector<Evicted>& evicted() const noexcept { return mEvicted; }
    void clearEvicted() { mEvicted.clear(); }

    /** @brief Keys from most to least recently used (tests and debugging; allocates). */
    std::vector<TileKey> lruOrder() const {
        std::vector<TileKey> out;
        for (std::uint32_t s = mHead; s != kNil; s = mSlots[s].next) out.push_back(mSlots[s].key);
        return out;
    }

private:
    static constexpr std::uint32_t kNil = 0xFFFFFFFFu;
    static constexpr std::uint32_t kGenerationMask = (1u << (32 - TileHandle::kIndexBits)) - 1u;

    struct Slot {
        // Held by pointer: the slot table is allocated (and touched) for every slot up front,
        // and a payload (a tile mesh's cell tables alone are ~600 bytes) inline in each of 4096
        // slots cost ~4 MB resident whether or not the slot is used (docs/performance.md).
        std::unique_ptr<T> payload;
        TileKey key;
        std::size_t cpuBytes = 0;
        std::size_t gpuBytes = 0;
        std::uint64_t lastUsed = 0;
        std::uint32_t generation = 1;
        std::uint32_t prev = kNil, next = kNil;
        bool used = false;
    };

    TileHandle makeHandle(std::uint32_t s) const {
        return TileHandle{(mSlots[s].generation << TileHandle::kIndexBits) | s};
    }
    std::uint32_t resolve(TileHandle h) const {
        if (!h.valid()) return kNil;
        const std::uint32_t s = h.index();
        if (s >= mSlots.size() || !mSlots[s].used || mSlots[s].generation != h.generation())
            return kNil;
        return s;
    }

    // Evict LRU unpinned entries (never `keep`) until cpu/gpu extra bytes fit and at least
    // `slotsNeeded` slots are free. Checks first so a refusal changes nothing.
    bool makeRoom(std::size_t cpuExtra, std::size_t gpuExtra, std::uint32_t keep,
                  std::size_t slotsNeeded) {
        auto fits = [&](std::size_t cpu, std::size_t gpu, std::size_t freed) {
            return cpu + cpuExtra <= mBudget.cpuBytes && gpu + gpuExtra <= mBudget.gpuBytes &&
                   mFree.size() + freed >= slotsNeeded;
        };
        std::size_t cpu = mCpu, gpu = mGpu, freed = 0;
        std::uint32_t s = mTail;
        std::uint32_t last = kNil;
        while (!fits(cpu, gpu, freed)) {
            while (s != kNil && (s == keep || mSlots[s].lastUsed == mFrame)) s = mSlots[s].prev;
            if (s == kNil) return false;
            cpu -= mSlots[s].cpuBytes;
            gpu -= mSlots[s].gpuBytes;
            ++freed;
            last = s;
            s = mSlots[s].prev;
        }
        if (last == kNil) return true;
        s = mTail;
        while (s != kNil) {
            const std::uint32_t prev = mSlots[s].prev;
            const bool evictable = s != keep && mSlots[s].lastUsed != mFrame;
            if (evictable) evictSlot(s);
            if (s == last) break;
            s = prev;
        }
        return true;
    }

    void evictSlot(std::uint32_t s) {
        Slot& slot = mSlots[s];
        mEvicted.push_back(Evicted{slot.key, makeHandle(s), slot.gpuBytes});
        tableErase(s);
        unlink(s);
        mCpu -= slot.cpuBytes;
        mGpu -= slot.gpuBytes;
        slot.payload.reset();
        slot.cpuBytes = slot.gpuBytes = 0;
        slot.used = false;
        slot.generation = (slot.generation + 1) & kGenerationMask;
        if (slot.generation == 0) slot.generation = 1;
        mFree.push_back(s);
        --mCount;
    }

    void unlink(std::uint32_t s) {
        Slot& slot = mSlots[s];
        if (slot.prev != kNil)
            mSlots[slot.prev].next = slot.next;
        else if (mHead == s)
            mHead = slot.next;
        if (slot.next != kNil)
            mSlots[slot.next].prev = slot.prev;
        else if (mTail == s)
            mTail = slot.prev;
        slot.prev = slot.next = kNil;
    }
    void pushFront(std::uint32_t s) {
        mSlots[s].prev = kNil;
        mSlots[s].next = mHead;
        if (mHead != kNil) mSlots[mHead].prev = s;
        mHead = s;
        if (mTail == kNil) mTail = s;
    }

    // Open addressing with linear probing and backward-shift deletion: no tombstones, no
    // allocation after construction.
    std::size_t bucketOf(const TileKey& key) const {
        return std::size_t(key.hash()) & (mTable.size() - 1);
    }
    std::uint32_t lookup(const TileKey& key) const {
        for (std::size_t b = bucketOf(key);; b = (b + 1) & (mTable.size() - 1)) {
            const std::uint32_t s = mTable[b];
            if (s == kNil) return kNil;
            if (mSlots[s].key == key) return s;
        }
    }
    void tableInsert(std::uint32_t s) {
        std::size_t b = bucketOf(mSlots[s].key);
        while (mTable[b] != kNil) b = (b + 1) & (mTable.size() - 1);
        mTable[b] = s;
    }
    void tableErase(std::uint32_t s) {
        const std::size_t mask = mTable.size() - 1;
        std::size_t b = bucketOf(mSlots[s].key);
        while (mTable[b] != s) b = (b + 1) & mask;
        std::size_t hole = b;
        for (std::size_t i = (hole + 1) & mask; mTable[i] != kNil; i = (i + 1) & mask) {
            const std::size_t home = bucketOf(mSlots[mTable[i]].key);
            // Move entry i into the hole if its home is not cyclically within (hole, i].
            const bool between =
                hole <= i ? (home > hole && home <= i) : (home > hole || home <= i);
            if (!between) {
                mTable[hole] = mTable[i];
                hole = i;
            }
        }
        mTable[hole] = kNil;
    }

    CacheBudget mBudget;
    std::vector<Slot> mSlots;
    std::vector<std::uint32_t> mTable;
    std::vector<std::uint32_t> mFree;
    std::vector<Evicted> mEvicted;
    std::uint32_t mHead = kNil, mTail = kNil;
    std::size_t mCpu = 0, mGpu = 0, mCount = 0;
    std::uint64_t mFrame = 0;
};

}  // namespace kiosk::terrain
