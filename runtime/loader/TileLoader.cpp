#include "runtime/loader/TileLoader.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <pthread.h>
#include <string>
#include <utility>

namespace kiosk::loader {

namespace {

bool lowerPriority(const LoadRequest& a, const LoadRequest& b) {
    return a.priority < b.priority;
}

std::string keyName(const terrain::TileKey& k) {
    return "layer " + std::to_string(k.layer) + " frame " + std::to_string(k.frame) + " tile " +
           std::to_string(k.id.level) + "/" + std::to_string(k.id.column) + "/" +
           std::to_string(k.id.row);
}

}  // namespace

TileLoader::TileLoader(LoaderOptions options, std::unique_ptr<LoadFunction> function)
    : mOptions(options), mFunction(std::move(function)) {
    mOptions.maxInFlight = std::max<std::uint32_t>(1, mOptions.maxInFlight);
    for (auto* v : {&mBatch, &mPrefetchBatch, &mShared, &mPrefetchShared, &mWork, &mPrefetchWork})
        v->reserve(mOptions.expectedRequests);
    mPending.reserve(mOptions.maxInFlight + 1);
    mRing.resize(mOptions.maxInFlight);
    mRingSlotBytes.assign(mOptions.maxInFlight, 0);
    mDelivered.resize(256 + 4 * std::size_t(mOptions.maxInFlight));
    if (mFunction) {
        mThread = std::thread([this] { run(); });
        // Named here, before the constructor returns, so a profile (top -H, bench-products'
        // CPU per thread) tells the loader apart from the moment it exists.
        pthread_setname_np(mThread.native_handle(), "kiosk-loader");
    }
}

TileLoader::~TileLoader() {
    shutdown();
}

void TileLoader::shutdown() {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mStop = true;
    }
    mWake.notify_all();
    if (mThread.joinable()) mThread.join();
}

void TileLoader::request(const terrain::TileKey& key, double priority) {
    mBatch.push_back(LoadRequest{key, priority, mGeneration.load() + 1, false});
}

void TileLoader::submit() {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        // A batch the loader never picked up comes back here: it is stale now.
        if (mSharedDirty) mCounters.droppedStale += mShared.size();
        std::swap(mBatch, mShared);
        mSharedDirty = true;
        mCounters.submitted += mShared.size();
        mGeneration.fetch_add(1);
    }
    mBatch.clear();
    mWake.notify_one();
}

void TileLoader::submit(const std::vector<terrain::TileRequest>& requests) {
    for (const auto& r : requests) request(r.key, r.priority);
    submit();
}

void TileLoader::prefetch(const std::vector<terrain::TileRequest>& requests) {
    mPrefetchBatch.clear();
    for (const auto& r : requests)
        mPrefetchBatch.push_back(LoadRequest{r.key, r.priority, mGeneration.load(), true});
    {
        std::lock_guard<std::mutex> lock(mMutex);
        if (mPrefetchDirty) mCounters.droppedStale += mPrefetchShared.size();
        std::swap(mPrefetchBatch, mPrefetchShared);
        mPrefetchDirty = true;
        mCounters.submitted += mPrefetchShared.size();
    }
    mPrefetchBatch.clear();
    mWake.notify_one();
}

bool TileLoader::tryPop(LoadResult& out) {
    std::unique_lock<std::mutex> lock(mMutex, std::try_to_lock);
    if (!lock.owns_lock() || mRingCount == 0) return false;
    out = std::move(mRing[mRingHead]);
    mRingBytes -= mRingSlotBytes[mRingHead];
    mRingSlotBytes[mRingHead] = 0;
    mRingHead = (mRingHead + 1) % std::uint32_t(mRing.size());
    --mRingCount;
    removePendingLocked(out.request.key);
    mDelivered[mDeliveredNext] = Delivered{out.request.key, mGeneration.load(), true};
    mDeliveredNext = (mDeliveredNext + 1) % mDelivered.size();
    ++mCounters.delivered;
    lock.unlock();
    mWake.notify_one();  // a completion slot is free again
    return true;
}

void TileLoader::invalidate() {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        ++mEpoch;
        mCounters.droppedStale += mShared.size() + mPrefetchShared.size();
        mShared.clear();
        mPrefetchShared.clear();
        mSharedDirty = mPrefetchDirty = true;
        while (mRingCount > 0) {
            removePendingLocked(mRing[mRingHead].request.key);
            mRing[mRingHead] = LoadResult{};
            mRingBytes -= mRingSlotBytes[mRingHead];
            mRingSlotBytes[mRingHead] = 0;
            mRingHead = (mRingHead + 1) % std::uint32_t(mRing.size());
            --mRingCount;
            ++mCounters.droppedInvalidated;
        }
        mGeneration.fetch_add(1);
    }
    mBatch.clear();
    mWake.notify_one();
}

LoaderCounters TileLoader::counters() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mCounters;
}

std::uint32_t TileLoader::inFlight() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mRingCount + (mLoading ? 1u : 0u);
}

std::uint32_t TileLoader::queued() const {
    std::lock_guard<std::mutex> lock(mMutex);
    // A dirty shared set replaces the work queue on the loader's next look; else work is current.
    return std::uint32_t((mSharedDirty ? mShared.size() : mWork.size()) +
                         (mPrefetchDirty ? mPrefetchShared.size() : mPrefetchWork.size()));
}

std::size_t TileLoader::heldBytes() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mRingBytes;
}

bool TileLoader::isPendingLocked(const terrain::TileKey& key) const {
    return std::find(mPending.begin(), mPending.end(), key) != mPending.end();
}

bool TileLoader::deliveredSinceLocked(const LoadRequest& request) const {
    for (const Delivered& d : mDelivered)
        if (d.valid && d.key == request.key && request.generation <= d.generation) return true;
    return false;
}

void TileLoader::removePendingLocked(const terrain::TileKey& key) {
    auto it = std::find(mPending.begin(), mPending.end(), key);
    if (it != mPending.end()) {
        *it = mPending.back();
        mPending.pop_back();
    }
}

void TileLoader::run() {
    mFunction->threadStarted();
    while (true) {
        LoadRequest req;
        std::uint64_t epoch = 0;
        {
            std::unique_lock<std::mutex> lock(mMutex);
            bool have = false;
            while (!mStop) {
                if (mSharedDirty) {
                    // The new frame's set replaces what is left of the old one.
                    std::swap(mShared, mWork);
                    mCounters.droppedStale += mShared.size();
                    mShared.clear();
                    mSharedDirty = false;
                    std::make_heap(mWork.begin(), mWork.end(), lowerPriority);
                }
                if (mPrefetchDirty) {
                    std::swap(mPrefetchShared, mPrefetchWork);
                    mCounters.droppedStale += mPrefetchShared.size();
                    mPrefetchShared.clear();
                    mPrefetchDirty = false;
                    std::make_heap(mPrefetchWork.begin(), mPrefetchWork.end(), lowerPriority);
                }
                // Room by count and by bytes (the first result is always allowed).
                const bool bytesFull = mOptions.maxBytesInFlight > 0 && mRingCount > 0 &&
                                       mRingBytes >= mOptions.maxBytesInFlight;
                const bool room = mRingCount < mOptions.maxInFlight && !bytesFull;
                std::vector<LoadRequest>* queue =
                    !mWork.empty() ? &mWork : (!mPrefetchWork.empty() ? &mPrefetchWork : nullptr);
                if (bytesFull && queue) ++mCounters.waitsForBytes;
                if (room && queue) {
                    std::pop_heap(queue->begin(), queue->end(), lowerPriority);
                    req = queue->back();
                    queue->pop_back();
                    if (isPendingLocked(req.key) || deliveredSinceLocked(req)) {
                        ++mCounters.droppedDuplicate;
                        continue;
                    }
                    mPending.push_back(req.key);
                    mLoading = true;
                    epoch = mEpoch;
                    have = true;
                    break;
                }
                mWake.wait(lock);
            }
            if (!have) break;
        }

        terrain::TilePayload payload;
        const auto loadStart = std::chrono::steady_clock::now();
        try {
            payload = mFunction->load(req);
        } catch (const std::exception& e) {
            payload = terrain::TilePayload{};
            payload.status = terrain::TilePayload::Status::Failed;
            payload.diagnostics.error("LOADER_EXCEPTION", "", keyName(req.key), e.what());
        } catch (...) {
            payload = terrain::TilePayload{};
            payload.status = terrain::TilePayload::Status::Failed;
            payload.diagnostics.error("LOADER_EXCEPTION", "", keyName(req.key),
                                      "unknown exception");
        }
        payload.key = req.key;
        const double loadSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();

        std::lock_guard<std::mutex> lock(mMutex);
        mLoading = false;
        ++mCounters.loaded;
        if (epoch != mEpoch || mStop) {
            removePendingLocked(req.key);
            if (!mStop) ++mCounters.droppedInvalidated;
            continue;
        }
        const std::uint32_t slot = (mRingHead + mRingCount) % std::uint32_t(mRing.size());
        const std::size_t bytes = payload.byteSize();
        mRing[slot] = LoadResult{req, std::move(payload), loadSeconds};
        mRingSlotBytes[slot] = bytes;
        mRingBytes += bytes;
        mCounters.heldBytesHigh = std::max<std::uint64_t>(mCounters.heldBytesHigh, mRingBytes);
        ++mRingCount;
    }
    mFunction->threadStopping();
}

}  // namespace kiosk::loader
