#pragma once

#include "runtime/terrain/TileKey.h"
#include "runtime/terrain/TilePayload.h"
#include "runtime/terrain/TileSelector.h"

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace kiosk::loader {

/** @brief One unit of work for the loader thread. */
struct LoadRequest {
    terrain::TileKey key;
    double priority = 0.0;         ///< larger first (screen-space error in pixels)
    std::uint64_t generation = 0;  ///< submission that (last) asked for it
    bool prefetch = false;
};

/**
 * @brief The work the loader thread runs, given once at setup (no per-frame std::function).
 * Called on the loader thread only: threadStarted() first (open the per-thread StoreReader
 * there), then load() per request, then threadStopping(). load() must not throw; if it does,
 * the result is a Failed payload with LOADER_EXCEPTION.
 */
class LoadFunction {
public:
    virtual ~LoadFunction() = default;
    virtual void threadStarted() {}
    virtual terrain::TilePayload load(const LoadRequest& request) = 0;
    virtual void threadStopping() {}
};

/** @brief A finished request handed to the render thread. */
struct LoadResult {
    LoadRequest request;
    terrain::TilePayload payload;
    double loadSeconds = 0.0;  ///< wall time load() took on the loader thread
};

struct LoaderOptions {
    /** @brief Max results not yet taken by tryPop plus the one being loaded (Cesium's
     * maximumSimultaneousTileLoads); bounds the memory of finished-but-not-uploaded tiles. */
    std::uint32_t maxInFlight = 8;
    /** @brief Initial capacity of the request vectors (they grow if a frame asks for more). */
    std::uint32_t expectedRequests = 1024;
    /**
     * @brief Bytes (TilePayload::byteSize) the results not yet taken by tryPop may hold: no new
     * load starts while they hold this much or more, so the decoded-but-not-uploaded payloads
     * stay under this plus one payload however far a slow render thread falls behind (tile
     * sizes vary 10x, a count alone does not bound them). One result is always allowed. 0: no
     * byte bound (maxInFlight only). docs/performance.md §5.
     */
    std::size_t maxBytesInFlight = std::size_t(4) << 20;
};

struct LoaderCounters {
    std::uint64_t submitted = 0;           ///< requests handed over by submit()/prefetch()
    std::uint64_t loaded = 0;              ///< load() calls that finished
    std::uint64_t delivered = 0;           ///< results taken by tryPop
    std::uint64_t droppedStale = 0;        ///< replaced by a newer submission before being started
    std::uint64_t droppedDuplicate = 0;    ///< key already loading or waiting in the completions
    std::uint64_t droppedInvalidated = 0;  ///< finished after invalidate(): never delivered
    std::uint64_t heldBytesHigh = 0;       ///< most bytes the completion ring held at once
    std::uint64_t waitsForBytes = 0;       ///< times the loader idled on maxBytesInFlight
};

/**
 * @brief One loader thread with a per-frame refreshed priority queue, generation-based
 * cancellation, a cap on in-flight work and a non-blocking completion queue.
 *
 * Render thread, each frame: request() the tiles the selector wants (or submit(requests)),
 * then submit(): the new set *replaces* everything queued before (latest screen-space error
 * wins; requests not repeated are stale and dropped without being loaded). prefetch() replaces
 * a separate low-priority set (a future camera's tiles) served only when the frame queue is
 * empty. tryPop() takes one finished result or returns false at once (it never waits, not even
 * for the lock). Skip keys that are already cached before requesting them.
 *
 * Each key is loaded at most once while it is in flight or waiting in the completion queue, and
 * every result is delivered exactly once. invalidate() (e.g. new scenario) drops all queued
 * requests and discards results of work started before it.
 *
 * The destructor (or shutdown()) drops pending requests, lets the current load() finish and
 * joins the thread. No allocation on the render side once the vectors have grown.
 */
class TileLoader {
public:
    TileLoader(LoaderOptions options, std::unique_ptr<LoadFunction> function);
    ~TileLoader();
    TileLoader(const TileLoader&) = delete;
    TileLoader& operator=(const TileLoader&) = delete;

    // Render thread.
    void request(const terrain::TileKey& key, double priority);
    void submit();
    /** @brief request() each of `requests` (after any added this frame), then submit(). */
    void submit(const std::vector<terrain::TileRequest>& requests);
    void prefetch(const std::vector<terrain::TileRequest>& requests);
    bool tryPop(LoadResult& out);
    void invalidate();
    void shutdown();

    /** @brief Generation of the latest submit(). */
    std::uint64_t generation() const noexcept { return mGeneration.load(); }
    LoaderCounters counters() const;
    /** @brief Loads running or finished but not yet popped. */
    std::uint32_t inFlight() const;
    /** @brief Requests handed over and not yet started (frame set plus prefetch set). */
    std::uint32_t queued() const;
    /** @brief Bytes held by finished results not yet popped (TilePayload::byteSize). */
    std::size_t heldBytes() const;
    const LoaderOptions& options() const noexcept { return mOptions; }

private:
    void run();
    bool isPendingLocked(const terrain::TileKey& key) const;
    bool deliveredSinceLocked(const LoadRequest& request) const;
    void removePendingLocked(const terrain::TileKey& key);

    LoaderOptions mOptions;
    std::unique_ptr<LoadFunction> mFunction;

    // Render thread only.
    std::vector<LoadRequest> mBatch;
    std::vector<LoadRequest> mPrefetchBatch;

    // Guarded by mMutex.
    mutable std::mutex mMutex;
    std::condition_variable mWake;
    std::vector<LoadRequest> mShared;
    std::vector<LoadRequest> mPrefetchShared;
    bool mSharedDirty = false;
    bool mPrefetchDirty = false;
    bool mStop = false;
    std::uint64_t mEpoch = 0;
    std::vector<terrain::TileKey> mPending;  // loading or in the completion ring
    std::vector<LoadResult> mRing;           // completion ring, capacity maxInFlight
    std::uint32_t mRingHead = 0, mRingCount = 0;
    std::size_t mRingBytes = 0;               // sum of byteSize() of the ring's results
    std::vector<std::size_t> mRingSlotBytes;  // per ring slot, capacity maxInFlight
    bool mLoading = false;
    LoaderCounters mCounters;
    // Recently delivered keys with the generation current at delivery: a queued request from a
    // submission no newer than that was made before the render thread had the result.
    struct Delivered {
        terrain::TileKey key;
        std::uint64_t generation = 0;
        bool valid = false;
    };
    std::vector<Delivered> mDelivered;  // fixed ring
    std::size_t mDeliveredNext = 0;

    // Loader thread only.
    std::vector<LoadRequest> mWork;
    std::vector<LoadRequest> mPrefetchWork;

    std::atomic<std::uint64_t> mGeneration{0};
    std::thread mThread;
};

}  // namespace kiosk::loader
