#pragma once

#include "runtime/math/Glm.h"
#include "runtime/terrain/RtinMesher.h"

#include <cstdint>
#include <vector>

namespace kiosk::terrain {

/** @brief A run of indices of a tile mesh: [first, first + count). */
struct IndexRange {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

/**
 * @brief Z-order code of cell (x, y) of a TileMesh (x bits at even, y bits at odd positions):
 * the four quadrants of any aligned block of cells have consecutive codes, so every quadtree
 * descendant of a tile down to TileMesh::kMaxCellLevels levels is one run of codes.
 */
std::uint32_t cellMortonCode(std::uint32_t x, std::uint32_t y);

/**
 * @brief World (CRS) xy rectangle holding every triangle of cell (x, y) of `mesh`, surface and
 * skirts: the cell's posts (pixel centres) plus the skirts' half-post flare on the tile border.
 */
void meshCellBounds(const TileMesh& mesh, int x, int y, glm::dvec2& min, glm::dvec2& max);

/**
 * @brief The index ranges of `mesh` whose cells intersect the world rectangle [rectMin, rectMax]
 * (surface cells first, then skirt cells, in index order; adjacent runs merged). Drawing these
 * ranges with the same rectangle as a fragment clip gives the same pixels as drawing the whole
 * mesh clipped, with the vertex and fragment work of the cells that matter only.
 *
 * `out` is cleared and refilled (no allocation once its capacity suffices). Returns false and
 * leaves `out` empty when the mesh has no cell layout (not built by RtinMesher); the caller then
 * draws the whole mesh. Pure function; any thread.
 */
bool meshRangesInRect(const TileMesh& mesh, const glm::dvec2& rectMin, const glm::dvec2& rectMax,
                      std::vector<IndexRange>& out);

}  // namespace kiosk::terrain
