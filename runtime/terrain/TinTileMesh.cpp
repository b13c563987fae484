#include "runtime/terrain/TinTileMesh.h"

#include <algorithm>

namespace kiosk::terrain {

Diagnostics TinMeshBuilder::build(const io::TinMesh& tin, const TileId& id,
                                  const io::TileGrid& grid, double tolerance, double skirtDepth,
                                  TileMesh& out) {
    Diagnostics d;
    if (id.level < 0 || id.level > grid.maxLevel()) {
        d.error("STORE_TIN_CORRUPT", "", "", "TIN of a level the grid does not have");
        return d;
    }
    const io::TileMatrix& m = grid.levels[std::size_t(id.level)];
    const int n = tin.postIntervals;
    if (n != m.tileWidth || n != m.tileHeight) {
        d.error("STORE_TIN_CORRUPT", "", "",
                "stored TIN is for " + std::to_string(n) + "-post tiles, the level's are " +
                    std::to_string(m.tileWidth));
        return d;
    }
    double x0, y0, x1, y1;
    grid.tileBounds(id, x0, y0, x1, y1);
    out.id = id;
    out.origin = glm::dvec3(x0, y1, 0.0);
    out.tolerance = tolerance;
    out.postSpacing = glm::dvec2(m.pixelXSize, m.pixelYSize);
    out.postIntervals = n;
    out.cellLevels = 0;
    out.cellPosts = n;
    const std::size_t count = tin.vertexCount();
    out.vertices.resize(count * TileMesh::kFloatsPerVertex);
    out.indices.assign(tin.indices.begin(), tin.indices.end());
    // MeshFinisher finds the border (for skirts) through each vertex's post: border vertices
    // are posts; a vertex between posts gets an inner post, so it never counts as border.
    mSurfacePost.resize(count);
    const double sub = double(io::kTinSubdivisions);
    const auto size = std::uint32_t(n + 1);
    for (std::size_t v = 0; v < count; ++v) {
        const double px = tin.xy[2 * v] / sub, py = tin.xy[2 * v + 1] / sub;
        float* o = &out.vertices[v * TileMesh::kFloatsPerVertex];
        o[0] = float((px + 0.5) * m.pixelXSize);
        o[1] = float(-(py + 0.5) * m.pixelYSize);
        o[2] = tin.z[v];
        o[3] = tin.normals[3 * v];
        o[4] = tin.normals[3 * v + 1];
        o[5] = tin.normals[3 * v + 2];
        std::uint32_t i = tin.xy[2 * v] / io::kTinSubdivisions;
        std::uint32_t j = tin.xy[2 * v + 1] / io::kTinSubdivisions;
        if (!tin.onPost(v)) {
            const auto inner = std::uint32_t(std::max(1, n - 1));
            i = std::max(1u, std::min(i, inner));
            j = std::max(1u, std::min(j, inner));
        }
        mSurfacePost[v] = j * size + i;
    }
    mFinisher.finish(out, mSurfacePost, skirtDepth);
    return d;
}

}  // namespace kiosk::terrain
