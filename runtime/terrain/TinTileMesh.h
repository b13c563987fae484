#pragma once

#include "runtime/core/Result.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/io/TinBlob.h"
#include "runtime/terrain/MeshFinish.h"
#include "runtime/terrain/TileMesh.h"

#include <cstdint>
#include <vector>

// A tile's local TIN (Baumann et al. 2000: a grid cell refined by a TIN) as the drawable mesh
// the renderer takes for any tile: positions relative to the tile's north-west corner, skirts
// along the border added exactly as for a grid mesh (MeshFinish.h). A TIN does not follow the
// mesh cells of a grid mesh, so it is one cell (cellLevels 0): a quadtree descendant drawn from
// it is clipped in the shader instead of picked by cell ranges.
namespace kiosk::terrain {

/** @brief Stored TIN -> drawable mesh. Keeps scratch buffers: one instance per thread. */
class TinMeshBuilder {
public:
    /**
     * @brief Build tile `id`'s mesh. STORE_TIN_CORRUPT when the TIN is not for the level's tile
     * size. `tolerance` is recorded in the mesh (the TIN's build tolerance).
     */
    Diagnostics build(const io::TinMesh& tin, const TileId& id, const io::TileGrid& grid,
                      double tolerance, double skirtDepth, TileMesh& out);

private:
    MeshFinisher mFinisher;
    std::vector<std::uint32_t> mSurfacePost;
};

}  // namespace kiosk::terrain
