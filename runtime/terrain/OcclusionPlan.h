#pragma once

#include "runtime/math/Camera.h"
#include "runtime/math/Frustum.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace kiosk::terrain {

/**
 * @brief Occlusion culling plan (Wahl et al. 2004 §5, docs/terrain.md §10); pure CPU, no GL.
 *
 * Tiles are drawn front to back. At a few points of that order ("rounds") the boxes of the next
 * batch of tiles are tested with occlusion queries against the depth of the nearer tiles
 * already drawn this frame; a tile none of whose box samples passes the depth test is skipped.
 * Same frame, never lagged: a query sees exactly the depth the tile itself would be tested
 * against, so a skipped tile cannot have drawn a pixel (no one-frame holes when the camera moves).
 */
struct OcclusionPlan {
    /** @brief Rounds per frame: each waits for the rasterizer once. */
    static constexpr int kRounds = 3;
    /** @brief Fewer tiles than this in a frame: nothing to gain, no queries. */
    static constexpr std::size_t kMinTiles = 8;

    /**
     * @brief Index into the front-to-back order at which each round starts (ascending): round r
     * tests tiles [start r, start r+1) (the last up to `tiles`); tiles before the first start are
     * drawn untested, they are the occluders of the first round. Empty below kMinTiles.
     */
    static std::vector<std::size_t> roundStarts(std::size_t tiles);

    /**
     * @brief The box to test for a tile whose drawn geometry lies inside `tight` (world metres,
     * z as drawn: vertical exaggeration applied), or nullopt when the tile must be drawn
     * untested: the enlarged box reaches the near plane (its front faces would be clipped away,
     * leaving only faces behind the tile) or contains the eye.
     *
     * The box is enlarged so that wherever the tile has a fragment the box has one in front of
     * it by more than float and 24-bit depth noise: by `minMargin` (a post spacing: the mesh's
     * cells and skirts, rasterisation snapping), by half a pixel at the box's far side, and by
     * eight steps of a 24-bit depth buffer at that distance (depth steps grow as distance² /
     * near plane).
     */
    static std::optional<math::Aabb> queryBox(const math::Camera& camera, const math::Aabb& tight,
                                              double minMargin);
};

}  // namespace kiosk::terrain
