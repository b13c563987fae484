#pragma once

#include <cstdint>
#include <functional>

namespace kiosk {

/**
 * @brief Address of one tile in a GeoPackage-style pyramid.
 *
 * `level` 0 is the coarsest (one tile covers the extent); `column` grows east, `row` grows
 * south, as in gpkg_tile_matrix (tile_column, tile_row).
 */
struct TileId {
    int level = 0;
    int column = 0;
    int row = 0;

    friend bool operator==(const TileId&, const TileId&) = default;
    friend auto operator<=>(const TileId&, const TileId&) = default;

    TileId parent() const noexcept { return {level - 1, column / 2, row / 2}; }
    TileId child(int quadrant) const noexcept {
        return {level + 1, column * 2 + (quadrant & 1), row * 2 + (quadrant >> 1)};
    }
    std::uint64_t packed() const noexcept {
        return (std::uint64_t(std::uint32_t(level)) << 58) |
               (std::uint64_t(std::uint32_t(column)) << 29) | std::uint64_t(std::uint32_t(row));
    }
};

}  // namespace kiosk

template <>
struct std::hash<kiosk::TileId> {
    std::size_t operator()(const kiosk::TileId& t) const noexcept {
        return std::hash<std::uint64_t>{}(t.packed());
    }
};
