#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/core/TileId.h"
#include "runtime/io/StoreReader.h"
#include "runtime/loader/Derivation.h"

#include <atomic>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace kiosk::loader {

/**
 * @brief Running states of cumulative derivations per (binding, tile), kept between requests
 * on the loader thread so playing forward folds in one stored frame per step.
 *
 * Per tile it keeps the latest state and a checkpoint every kCheckpointEvery frames; a request
 * for frame k resumes from the latest kept state at or before k (a seek backwards costs at most
 * kCheckpointEvery - 1 frames once the checkpoints exist, a cold seek k + 1 frames). The bytes
 * held stay under the budget: the checkpoints of the least recently used tiles are dropped
 * first (a seek backwards there restarts from frame 0), then whole tiles, least recently used
 * first. Correctness never depends on what is kept: any state is recomputable from frame 0. The
 * budget always holds the latest state (and next frame) of the tiles the view draws now
 * (setTracksInView): with fewer kept, every step would restart each of them from frame 0
 * (k + 2 frame reads per tile and step).
 */
class DerivedTiles {
public:
    static constexpr int kCheckpointEvery = 16;

    /** @brief Bytes the states may hold at least (any thread). */
    void setBudget(std::size_t bytes) noexcept {
        mBudget.value.store(bytes, std::memory_order_relaxed);
    }
    /**
     * @brief (tile, product layer) pairs the view draws now (any thread, e.g. the render thread
     * every frame): the budget then holds at least that many latest states and next frames
     * (the largest seen), not their checkpoints.
     */
    void setTracksInView(std::size_t tracks) noexcept {
        mTracksInView.value.store(tracks, std::memory_order_relaxed);
    }
    /** @brief The bytes the states may hold now (loader thread). */
    std::size_t budget() const noexcept;
    std::size_t bytes() const noexcept { return mBytes; }
    /** @brief bytes() after the last computation, readable from any thread (metrics). */
    std::size_t bytesHeld() const noexcept {
        return mBytesHeld.value.load(std::memory_order_relaxed);
    }
    /** @brief Stored frames folded into states so far (loader thread): what recomputing costs. */
    std::uint64_t framesFolded() const noexcept { return mFolded; }

    /**
     * @brief The product tile of frame `frame` of `sequence` on tile `id` (binding `binding`)
     * into `out` (Derivation::kProductChannels floats per post: the state after the frame and
     * the frame pair), reading frames from `reader`. Errors name the frame read.
     */
    Diagnostics compute(int binding, const Derivation& d, io::StoreReader& reader,
                        const std::string& sequence, int frame, const TileId& id,
                        io::RasterTile& out);

private:
    struct Key {
        int binding;
        std::uint64_t tile;
        auto operator<=>(const Key&) const = default;
    };
    struct Track {
        std::map<int, std::vector<float>> states;  ///< by frame folded in last
        std::uint64_t lastUse = 0;
        std::size_t bytes = 0;
        int postsX = 0, postsY = 0;  ///< the tile's raster size (every frame's)
        int nextFrame = -1;          ///< frame held in `next` (read as the pair's second)
        std::vector<float> next;
    };
    void keep(Track& t, int frame, const std::vector<float>& state);
    void evict(const Key& keepKey);

    std::map<Key, Track> mTracks;
    /** @brief Shared with another thread than the loader's; copyable so an idle loader moves. */
    struct SharedSize {
        std::atomic<std::size_t> value;
        explicit SharedSize(std::size_t v) noexcept : value(v) {}
        SharedSize(const SharedSize& o) noexcept : value(o.value.load()) {}
        SharedSize& operator=(const SharedSize& o) noexcept {
            value.store(o.value.load());
            return *this;
        }
    };
    SharedSize mBudget{std::size_t(64) << 20};
    SharedSize mTracksInView{0};
    SharedSize mBytesHeld{0};
    std::size_t mBytes = 0;
    std::size_t mLargestRunning = 0;  ///< largest latest state + next frame of a tile, bytes
    std::uint64_t mFolded = 0;
    std::uint64_t mUse = 0;
};

}  // namespace kiosk::loader
