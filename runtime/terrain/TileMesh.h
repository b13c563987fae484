#pragma once

#include "runtime/core/TileId.h"
#include "runtime/math/Glm.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace kiosk::terrain {

/**
 * @brief A tile's triangle mesh ready for a GL vertex buffer (no GL here).
 *
 * Vertex layout (interleaved, 24 bytes, matches runtime/shaders/terrain.vert):
 *   location 0: float3 position, metres relative to `origin` (x east, y north, z up)
 *   location 1: float3 normal, unit length, computed from the full-resolution posts
 * `origin` is the tile's north-west corner (TileGrid::tileBounds x0, y1) at z = 0. Posts sit at
 * pixel centres: post (i, j) is at x = (i + 0.5) * pixelX, y = -(j + 0.5) * pixelY.
 *
 * Indices are uint32 triangles (a full-resolution 257x257 tile has more than 65535 vertices).
 * Surface triangles come first (`surfaceIndexCount` indices, counter-clockwise seen from above),
 * then skirt triangles (counter-clockwise seen from outside the tile; draw skirts without face
 * culling or keep culling off for the whole tile). Skirt vertices follow the surface vertices.
 *
 * Cells: the tile is divided into `cellsPerSide()`^2 square cells of `cellPosts` post
 * intervals (8x8 for tiles of 64 or more post intervals). Every triangle lies inside one cell
 * (the mesher splits at least that far) and both the surface and the skirt triangles are sorted
 * by the cells' Morton (Z-order) code, so any quadtree descendant of the tile down to
 * `cellLevels` levels is one contiguous index range of each section (see MeshCells.h).
 * Surface cell c is indices [surfaceCellStart[c], surfaceCellStart[c+1]); skirt cell c is
 * [skirtCellStart[c], skirtCellStart[c+1]) (skirt ranges start at surfaceIndexCount).
 */
struct TileMesh {
    static constexpr int kFloatsPerVertex = 6;
    static constexpr std::size_t kVertexStride = kFloatsPerVertex * sizeof(float);
    /** @brief Quadtree levels the cell ordering resolves (8x8 cells). */
    static constexpr int kMaxCellLevels = 3;
    static constexpr int kMaxCells = 1 << (2 * kMaxCellLevels);

    TileId id;
    glm::dvec3 origin{0.0};
    std::vector<float> vertices;
    std::vector<std::uint32_t> indices;
    std::uint32_t surfaceVertexCount = 0;
    std::uint32_t surfaceIndexCount = 0;
    float minZ = 0.0f;  ///< over surface vertices (metres, absolute: origin.z is 0)
    float maxZ = 0.0f;
    double tolerance = 0.0;  ///< TIN tolerance the mesh was built with (metres)
    double skirtDepth = 0.0;
    glm::dvec2 postSpacing{0.0};  ///< metres between posts (x east, y south)
    int postIntervals = 0;        ///< posts per side - 1
    int cellLevels = 0;           ///< cells per side = 2^cellLevels (<= kMaxCellLevels)
    int cellPosts = 0;            ///< post intervals per cell side
    std::array<std::uint32_t, kMaxCells + 1> surfaceCellStart{};
    std::array<std::uint32_t, kMaxCells + 1> skirtCellStart{};

    int cellsPerSide() const noexcept { return 1 << cellLevels; }
    int cellCount() const noexcept { return 1 << (2 * cellLevels); }

    std::size_t vertexCount() const noexcept { return vertices.size() / kFloatsPerVertex; }
    std::size_t triangleCount() const noexcept { return indices.size() / 3; }
    std::size_t surfaceTriangleCount() const noexcept { return surfaceIndexCount / 3; }
    std::size_t skirtTriangleCount() const noexcept {
        return triangleCount() - surfaceTriangleCount();
    }
    /** @brief Bytes of vertex + index data (what a GL upload of this mesh costs). */
    std::size_t byteSize() const noexcept {
        return vertices.size() * sizeof(float) + indices.size() * sizeof(std::uint32_t);
    }
};

}  // namespace kiosk::terrain
