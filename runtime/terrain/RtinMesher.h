#pragma once

#include "runtime/core/Result.h"
#include "runtime/core/TileId.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/math/Glm.h"
#include "runtime/terrain/TerrainOptions.h"

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

/** @brief Where a raster tile sits and how to triangulate it. */
struct MeshParams {
    double originX = 0.0;     ///< tile's west edge (CRS metres)
    double originY = 0.0;     ///< tile's north edge
    double pixelX = 1.0;      ///< post spacing east (metres)
    double pixelY = 1.0;      ///< post spacing south (metres)
    double tolerance = 0.0;   ///< max vertical deviation of the TIN from the posts (metres)
    double skirtDepth = 0.0;  ///< how far skirts hang below the border (metres); 0 = no skirts

    /** @brief Params for tile `id` of `grid` using `options` and the tile's stored error. */
    static MeshParams forTile(const io::TileGrid& grid, const TileId& id,
                              const TerrainOptions& options, double tileError, int tier = 0);
};

/**
 * @brief Right-triangulated irregular network (RTIN) builder for (2^k+1)^2 post grids.
 *
 * Bottom-up pass: for every triangle of the RTIN hierarchy, the exact maximum vertical
 * deviation of its plane from every post it covers (NaN post = infinite), propagated to its
 * ancestors and shared across the hypotenuse, so the top-down extraction yields a conforming
 * (crack-free) mesh whose every post is within `tolerance` of the surface. Triangles touching a
 * NaN post are dropped (holes) and no skirt is emitted along a dropped border edge.
 *
 * Threads: one instance per thread (it keeps scratch buffers so repeated builds do not
 * allocate once warm). Never throws; a wrongly shaped tile gives TERRAIN_TILE_SHAPE.
 */
class RtinMesher {
public:
    /** @brief Build into `out` (its buffers are reused). */
    Diagnostics build(const io::RasterTile& tile, const MeshParams& params, TileMesh& out);
    Result<TileMesh> build(const io::RasterTile& tile, const MeshParams& params);

private:
    void computeErrors(int ax, int ay, int bx, int by, int cx, int cy, int depth, int target);
    float triangleError(int ax, int ay, int bx, int by, int cx, int cy) const;
    void extract(int ax, int ay, int bx, int by, int cx, int cy);
    void sortByCell(TileMesh& out, std::uint32_t begin, std::uint32_t end, std::size_t group,
                    std::array<std::uint32_t, TileMesh::kMaxCells + 1>& starts);
    void emitTriangle(int ax, int ay, int bx, int by, int cx, int cy);
    std::uint32_t vertexFor(int x, int y);
    std::uint32_t skirtVertexFor(std::uint32_t top);
    float post(int x, int y) const {
        return mPosts[std::size_t(y) * std::size_t(mSize) + std::size_t(x)];
    }

    const float* mPosts = nullptr;
    int mSize = 0;       // posts per side (2^k + 1)
    int mCellPosts = 1;  // triangles are split until they fit one cell of this many intervals
    double mTolerance = 0.0;
    bool mHasNodata = false;
    MeshParams mParams;
    TileMesh* mOut = nullptr;
    std::vector<float> mErrors;               // per post: error of the triangles split there
    std::vector<std::int32_t> mVertexIndex;   // per post: vertex index or -1
    std::vector<std::int32_t> mSkirtIndex;    // per surface vertex: skirt vertex or -1
    std::vector<std::uint32_t> mSurfacePost;  // per surface vertex: post index
    std::vector<std::uint32_t> mSortScratch;  // indices while sorting by cell
    std::vector<std::uint16_t> mGroupCell;    // per triangle/quad: Morton code of its cell
};

/**
 * @brief Convenience for the loader: mesh of an elevation tile with the tolerance and skirt
 * depth that `options` prescribe for its level and tolerance tier (the elevation key's frame;
 * errors name the tile).
 */
Result<TileMesh> buildTileMesh(const io::RasterTile& tile, const io::TileGrid& grid,
                               const TerrainOptions& options, RtinMesher& mesher, int tier = 0);

}  // namespace kiosk::terrain
