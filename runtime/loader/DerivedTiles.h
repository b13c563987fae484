#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/core/TileId.h"
#include "runtime/io/StoreReader.h"
#include "runtime/loader/Derivation.h"

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
 * held stay under the budget: whole tiles are dropped least recently used first. Correctness
 * never depends on what is kept: any state is recomputable from frame 0.
 */
class DerivedTiles {
public:
    static constexpr int kCheckpointEvery = 16;

    void setBudget(std::size_t bytes) noexcept { mBudget = bytes; }
    std::size_t bytes() const noexcept { return mBytes; }

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
    std::size_t mBudget = 64u << 20;
    std::size_t mBytes = 0;
    std::uint64_t mUse = 0;
};

}  // namespace kiosk::loader
