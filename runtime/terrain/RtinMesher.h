#pragma once

#include "runtime/core/Result.h"
#include "runtime/core/TileId.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/math/Glm.h"
#include "runtime/terrain/MeshFinish.h"
#include "runtime/terrain/TerrainOptions.h"
#include "runtime/terrain/TileMesh.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace kiosk::terrain {

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
    /**
     * @brief After a build: the largest split error of the tile (infinite next to nodata). When
     * it is at most the build's tolerance the mesh is the tile's coarsest (two triangles a
     * cell): every larger tolerance gives the same mesh.
     */
    float maxSplitError() const;
    /**
     * @brief Make the next builds compute every split error exactly (slower: no early exit once
     * a triangle is known to exceed the tolerance). The mesh is the same; slotError() then tells
     * at which larger tolerances each vertex would still be split (stored meshes, StoredMesh.h).
     */
    void setExactErrors(bool exact) noexcept { mExactErrors = exact; }
    /** @brief After a build: split error of the triangles whose hypotenuse midpoint is `post`. */
    float slotError(std::size_t post) const { return mErrors[post]; }
    /** @brief After a build: post index (row * posts per side + column) of surface vertex v. */
    const std::vector<std::uint32_t>& surfacePosts() const noexcept { return mSurfacePost; }

private:
    void computeErrors(int ax, int ay, int bx, int by, int cx, int cy, int depth, int target);
    float triangleError(int ax, int ay, int bx, int by, int cx, int cy) const;
    void extract(int ax, int ay, int bx, int by, int cx, int cy);
    void emitTriangle(int ax, int ay, int bx, int by, int cx, int cy);
    std::uint32_t vertexFor(int x, int y);
    float post(int x, int y) const {
        return mPosts[std::size_t(y) * std::size_t(mSize) + std::size_t(x)];
    }

    const float* mPosts = nullptr;
    int mSize = 0;       // posts per side (2^k + 1)
    int mCellPosts = 1;  // triangles are split until they fit one cell of this many intervals
    double mTolerance = 0.0;
    bool mHasNodata = false;
    bool mExactErrors = false;
    MeshParams mParams;
    TileMesh* mOut = nullptr;
    std::vector<float> mErrors;               // per post: error of the triangles split there
    std::vector<std::int32_t> mVertexIndex;   // per post: vertex index or -1
    std::vector<std::uint32_t> mSurfacePost;  // per surface vertex: post index
    MeshFinisher mFinisher;                   // cell order, z range, skirts
};

/**
 * @brief Convenience for the loader: mesh of an elevation tile with the tolerance and skirt
 * depth that `options` prescribe for its level and tolerance tier (the elevation key's frame;
 * errors name the tile).
 */
Result<TileMesh> buildTileMesh(const io::RasterTile& tile, const io::TileGrid& grid,
                               const TerrainOptions& options, RtinMesher& mesher, int tier = 0);

}  // namespace kiosk::terrain
