#pragma once

#include "runtime/terrain/TileMesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace kiosk::terrain {

/**
 * @brief The part of a TileMesh that follows from its surface triangles: cell order of the
 * surface, z range, skirts along the tile border and their cell order. Shared by the RTIN builder
 * and the stored-mesh decoder (StoredMesh.h) so both give the same drawable mesh.
 *
 * Before finish(), `out` holds the surface vertices and triangles (counter-clockwise seen from
 * above) and its postIntervals, postSpacing, cellLevels and cellPosts; `surfacePost[v]` is the
 * post index (row * (postIntervals + 1) + column) of surface vertex v. Keeps scratch buffers:
 * one instance per thread.
 */
class MeshFinisher {
public:
    void finish(TileMesh& out, const std::vector<std::uint32_t>& surfacePost, double skirtDepth);

private:
    void sortByCell(TileMesh& out, std::uint32_t begin, std::uint32_t end, std::size_t group,
                    std::array<std::uint32_t, TileMesh::kMaxCells + 1>& starts);
    std::uint32_t skirtVertexFor(TileMesh& out, std::uint32_t top, double skirtDepth);

    const std::vector<std::uint32_t>* mSurfacePost = nullptr;
    int mSize = 0;                            // posts per side
    std::vector<std::int32_t> mSkirtIndex;    // per surface vertex: skirt vertex or -1
    std::vector<std::uint32_t> mSortScratch;  // indices while sorting by cell
    std::vector<std::uint16_t> mGroupCell;    // per triangle/quad: Morton code of its cell
};

}  // namespace kiosk::terrain
