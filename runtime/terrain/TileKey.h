#pragma once

#include "runtime/core/TileId.h"

#include <cstdint>
#include <functional>

namespace kiosk::terrain {

/**
 * @brief Identity of one cached / requested tile payload: which layer (an index the application
 * assigns at setup, e.g. 0 = elevation, 1.. = texture layers), which frame of a time-keyed
 * sequence (0 for static layers) and which tile.
 */
struct TileKey {
    std::uint16_t layer = 0;
    std::int32_t frame = 0;
    TileId id;

    friend bool operator==(const TileKey&, const TileKey&) = default;

    std::uint64_t hash() const noexcept {
        // splitmix64 over the packed tile id, salted with layer and frame.
        std::uint64_t x = id.packed() ^ (std::uint64_t(layer) << 48) ^
                          (std::uint64_t(std::uint32_t(frame)) * 0x9E3779B97F4A7C15ull);
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
        return x ^ (x >> 31);
    }
};

/**
 * @brief Generation-checked reference to a cache slot (sokol-style): the low 20 bits are the
 * slot index, the high 12 bits the slot's generation when the handle was made. 0 is invalid.
 * A handle whose slot has since been evicted and reused no longer resolves (stale detection).
 */
struct TileHandle {
    std::uint32_t id = 0;

    static constexpr std::uint32_t kIndexBits = 20;
    static constexpr std::uint32_t kIndexMask = (1u << kIndexBits) - 1u;

    bool valid() const noexcept { return id != 0; }
    std::uint32_t index() const noexcept { return id & kIndexMask; }
    std::uint32_t generation() const noexcept { return id >> kIndexBits; }
    friend bool operator==(const TileHandle&, const TileHandle&) = default;
};

}  // namespace kiosk::terrain

template <>
struct std::hash<kiosk::terrain::TileKey> {
    std::size_t operator()(const kiosk::terrain::TileKey& k) const noexcept {
        return std::size_t(k.hash());
    }
};
