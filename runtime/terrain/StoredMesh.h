#pragma once

#include "runtime/core/Result.h"
#include "runtime/io/MeshBlob.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/terrain/MeshFinish.h"
#include "runtime/terrain/RtinMesher.h"
#include "runtime/terrain/TileMesh.h"

#include <cstdint>
#include <vector>

// Tile meshes simplified at import and kept in the store (Wahl et al. 2004, sections 3-4): the
// importer quantises the RTIN surface it would build on load, the loader turns the stored form
// back into the same drawable mesh without reading or meshing the posts.
namespace kiosk::terrain {

/**
 * @brief The surface of a built mesh (skirts dropped) in store units. Heights are kept exactly:
 * q = (z - minZ) / zStep must be an integer <= 65535 for every vertex (true for meshes built from
 * a store layer whose quantisation step is `zStep`, a power of two), else TERRAIN_MESH_QUANTISE.
 */
Result<io::QuantizedMesh> quantizeSurface(const TileMesh& mesh, double zStep);

/**
 * @brief QuantizedMesh::splitTiers of the mesh `mesher` just built with `tolerance` (exact
 * errors, RtinMesher::setExactErrors): per surface vertex, the first tier k whose tolerance
 * (tolerance * 2^k, as TerrainOptions::tinTolerance) its split error does not exceed.
 */
std::vector<std::uint16_t> splitTiersOf(const RtinMesher& mesher, double tolerance);

/**
 * @brief Stored surface -> drawable TileMesh of tile `id` (positions as the RTIN builder makes
 * them, skirts of `skirtDepth` added as it adds them). Checks what the blob decoder cannot: the
 * post grid is the level's tile size and no triangle crosses a cell (STORE_MESH_CORRUPT).
 * Keeps scratch buffers: one instance per thread.
 */
class StoredMeshBuilder {
public:
    Diagnostics build(const io::QuantizedMesh& stored, const TileId& id, const io::TileGrid& grid,
                      double tolerance, double skirtDepth, TileMesh& out);
    /**
     * @brief Same for tolerance tier `tier` > 0 of a stored tier-0 mesh with splitTiers: the
     * RTIN extraction RtinMesher runs, deciding each split from the stored tiers instead of the
     * posts, so the result equals the mesh built from the posts at `tolerance` (= the stored
     * tolerance * 2^tier). STORE_MESH_CORRUPT when the mesh has no split tiers.
     */
    Diagnostics derive(const io::QuantizedMesh& stored, int tier, const TileId& id,
                       const io::TileGrid& grid, double tolerance, double skirtDepth,
                       TileMesh& out);

private:
    Diagnostics begin(const io::QuantizedMesh& stored, const TileId& id, const io::TileGrid& grid,
                      double tolerance, TileMesh& out);
    void extract(int ax, int ay, int bx, int by, int cx, int cy);
    std::uint32_t vertexFor(int x, int y);

    MeshFinisher mFinisher;
    std::vector<std::uint32_t> mSurfacePost;
    // derive(): per post the stored vertex (or -1) and its split tier; per stored vertex its
    // output index (or -1).
    const io::QuantizedMesh* mStored = nullptr;
    TileMesh* mOut = nullptr;
    int mSize = 0, mTier = 0, mCellPosts = 1;
    std::vector<std::int32_t> mPostVertex, mOutIndex;
    std::vector<std::uint16_t> mPostTier;
};

}  // namespace kiosk::terrain
