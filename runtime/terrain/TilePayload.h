#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/io/TextureBlocks.h"
#include "runtime/terrain/RtinMesher.h"
#include "runtime/terrain/TileCache.h"
#include "runtime/terrain/TileKey.h"
#include "runtime/terrain/TileSelector.h"

#include <cstddef>
#include <optional>

namespace kiosk::terrain {

/**
 * @brief What the loader produces for one TileKey and the cache holds (CPU side).
 * Exactly one of mesh / image / compressed / raster is set for Ready payloads. Absent: the store
 * has no such tile (draw nothing / neutral, do not request again). Failed: corrupt or unreadable
 * tile (diagnostics name it); treated like Absent by the selector so it is not re-requested.
 */
struct TilePayload {
    enum class Status { Ready, Absent, Failed };

    TileKey key;
    Status status = Status::Ready;
    std::optional<TileMesh> mesh;          ///< elevation layers
    std::optional<io::ImageTile> image;    ///< imagery layers
    /** @brief Imagery layers as GPU blocks stored at import (instead of `image`). */
    std::optional<io::CompressedImage> compressed;
    std::optional<io::RasterTile> raster;  ///< sequence frames (data values for a colour LUT)
    std::optional<io::TileStats> stats;    ///< elevation tiles: feed TileStatsTable
    Diagnostics diagnostics;

    /** @brief CPU bytes held (what the cache budget counts). */
    std::size_t byteSize() const noexcept {
        std::size_t b = sizeof(TilePayload);
        if (mesh) b += mesh->byteSize();
        if (image) b += image->rgba.size();
        if (compressed) b += compressed->blocks.size();
        if (raster) b += raster->values.size() * sizeof(float);
        return b;
    }
};

using TerrainTileCache = TileCache<TilePayload>;

/**
 * @brief TileResidency over a TerrainTileCache: a payload is drawable when it is cached and,
 * if `requireGpu`, the renderer has reserved GPU bytes for it (i.e. uploaded it). Absent and
 * Failed payloads count as drawable (the renderer draws nothing or a neutral colour for them),
 * so the selector stops requesting them. acquire() pins what the selector picks for the frame.
 * Render thread only.
 */
class CacheResidency final : public TileResidency {
public:
    /** @brief `pin` = false for a look-ahead selection (prefetch) that must not pin tiles. */
    CacheResidency(TerrainTileCache& cache, bool requireGpu, bool pin = true)
        : mCache(cache), mRequireGpu(requireGpu), mPin(pin) {}
    TileHandle drawable(const TileKey& key) override {
        const TileHandle h = mCache.find(key);
        if (!h.valid()) return {};
        const TilePayload* p = mCache.get(h);
        const bool ready =
            p->status != TilePayload::Status::Ready || !mRequireGpu || mCache.gpuBytesOf(h) > 0;
        if (!ready) return {};
        if (mPin) mCache.touch(h);
        return h;
    }

private:
    TerrainTileCache& mCache;
    bool mRequireGpu;
    bool mPin;
};

}  // namespace kiosk::terrain
