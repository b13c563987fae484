#pragma once

#include "runtime/core/TileId.h"
#include "runtime/io/StoreTypes.h"

#include <cstddef>
#include <unordered_map>

namespace kiosk::terrain {

/** @brief What the renderer knows about one elevation tile. */
enum class TileState { Unknown, Known, Absent };

/**
 * @brief Per-tile min/max/error of the elevation layer as known to the render thread.
 *
 * Filled from payloads as tiles arrive (their RasterTile carries TileStats) and, ideally, up
 * front by the application from StoreReader::tileStats for the upper levels so the selector's
 * guarantee holds from the first frame. Tiles the store lacks (STORE_TILE_MISSING, outside the
 * data extent) are marked Absent and never drawn or requested. The selector treats Unknown tiles
 * as having their parent's bounds and error.
 *
 * Threads: render thread only (no locking). Lookups never allocate; set() may.
 */
class TileStatsTable {
public:
    void set(const TileId& id, const io::TileStats& stats) { mMap[id] = Entry{stats, true}; }
    void markAbsent(const TileId& id) { mMap[id] = Entry{{}, false}; }
    void erase(const TileId& id) { mMap.erase(id); }
    void clear() { mMap.clear(); }
    std::size_t size() const noexcept { return mMap.size(); }

    TileState lookup(const TileId& id, io::TileStats& out) const {
        auto it = mMap.find(id);
        if (it == mMap.end()) return TileState::Unknown;
        if (!it->second.present) return TileState::Absent;
        out = it->second.stats;
        return TileState::Known;
    }

private:
    struct Entry {
        io::TileStats stats;
        bool present = true;
    };
    std::unordered_map<TileId, Entry> mMap;
};

}  // namespace kiosk::terrain
