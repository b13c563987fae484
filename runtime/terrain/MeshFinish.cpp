#include "runtime/terrain/MeshFinish.h"

#include "runtime/terrain/MeshCells.h"

#include <algorithm>

namespace kiosk::terrain {

std::uint32_t MeshFinisher::skirtVertexFor(TileMesh& out, std::uint32_t top, double skirtDepth) {
    if (mSkirtIndex[top] >= 0) return std::uint32_t(mSkirtIndex[top]);
    const std::uint32_t p = (*mSurfacePost)[top];
    const int x = int(p % std::uint32_t(mSize)), y = int(p / std::uint32_t(mSize));
    const int last = mSize - 1;
    const double pixelX = out.postSpacing.x, pixelY = out.postSpacing.y;
    // Bottoms flare half a post outward: tiles of a coarser level start half of *their* post
    // spacing further east/south, and the flare closes that horizontal gap seen from above.
    const double ox = x == 0 ? -0.5 * pixelX : (x == last ? 0.5 * pixelX : 0.0);
    const double oy = y == 0 ? 0.5 * pixelY : (y == last ? -0.5 * pixelY : 0.0);
    const std::size_t base = std::size_t(top) * TileMesh::kFloatsPerVertex;
    float v[TileMesh::kFloatsPerVertex];
    for (int i = 0; i < TileMesh::kFloatsPerVertex; ++i) v[i] = out.vertices[base + std::size_t(i)];
    v[0] = float(v[0] + ox);
    v[1] = float(v[1] + oy);
    v[2] = float(v[2] - skirtDepth);
    const auto index = std::uint32_t(out.vertices.size() / TileMesh::kFloatsPerVertex);
    out.vertices.insert(out.vertices.end(), v, v + TileMesh::kFloatsPerVertex);
    mSkirtIndex[top] = std::int32_t(index);
    return index;
}

void MeshFinisher::sortByCell(TileMesh& out, std::uint32_t begin, std::uint32_t end,
                              std::size_t group,
                              std::array<std::uint32_t, TileMesh::kMaxCells + 1>& starts) {
    // Counting sort of index groups (a triangle, or a skirt quad) by the Morton code of the cell
    // holding their first edge's midpoint; stable, so each cell keeps the extraction order.
    const std::vector<std::uint32_t>& surfacePost = *mSurfacePost;
    const int cells = out.cellCount();
    const std::size_t groups = (end - begin) / group;
    mGroupCell.resize(groups);
    std::array<std::uint32_t, TileMesh::kMaxCells + 1> count{};
    const std::uint32_t last = std::uint32_t(out.cellsPerSide() - 1);
    for (std::size_t g = 0; g < groups; ++g) {
        // A triangle's centroid lies inside its cell; a skirt quad {u, vs, v, u, us, vs} belongs
        // to the cell of its top edge (u, v), whose midpoint may sit on the east/south border.
        const std::uint32_t* idx = &out.indices[begin + g * group];
        const std::uint32_t corners[3] = {idx[0], idx[group == 3 ? 1 : 2], idx[2]};
        const int used = group == 3 ? 3 : 2;
        std::uint32_t sx = 0, sy = 0;
        for (int c = 0; c < used; ++c) {
            const std::uint32_t p = surfacePost[corners[c]];
            sx += p % std::uint32_t(mSize);
            sy += p / std::uint32_t(mSize);
        }
        const std::uint32_t span = std::uint32_t(used) * std::uint32_t(out.cellPosts);
        const std::uint32_t cx = std::min(sx / span, last), cy = std::min(sy / span, last);
        const std::uint16_t code = std::uint16_t(cellMortonCode(cx, cy));
        mGroupCell[g] = code;
        ++count[code];
    }
    starts[0] = begin;
    for (int c = 0; c < TileMesh::kMaxCells; ++c)
        starts[std::size_t(c) + 1] =
            starts[std::size_t(c)] + (c < cells ? count[std::size_t(c)] * std::uint32_t(group) : 0);
    std::array<std::uint32_t, TileMesh::kMaxCells> cursor{};
    for (int c = 0; c < TileMesh::kMaxCells; ++c) cursor[std::size_t(c)] = starts[std::size_t(c)];
    mSortScratch.assign(out.indices.begin() + begin, out.indices.begin() + end);
    for (std::size_t g = 0; g < groups; ++g) {
        std::uint32_t& dst = cursor[mGroupCell[g]];
        for (std::size_t i = 0; i < group; ++i) out.indices[dst + i] = mSortScratch[g * group + i];
        dst += std::uint32_t(group);
    }
}

void MeshFinisher::finish(TileMesh& out, const std::vector<std::uint32_t>& surfacePost,
                          double skirtDepth) {
    mSurfacePost = &surfacePost;
    mSize = out.postIntervals + 1;
    const int n = out.postIntervals;
    out.skirtDepth = skirtDepth;
    out.surfaceVertexCount = std::uint32_t(out.vertexCount());
    out.surfaceIndexCount = std::uint32_t(out.indices.size());
    sortByCell(out, 0, out.surfaceIndexCount, 3, out.surfaceCellStart);
    out.minZ = out.maxZ = 0.0f;
    for (std::size_t v = 0; v < out.vertexCount(); ++v) {
        const float z = out.vertices[v * TileMesh::kFloatsPerVertex + 2];
        if (v == 0 || z < out.minZ) out.minZ = z;
        if (v == 0 || z > out.maxZ) out.maxZ = z;
    }

    if (skirtDepth > 0) {
        // At most one skirt vertex per border post and one quad per border edge: one
        // allocation (page faults of growing megabyte buffers cost more than the work here).
        out.vertices.reserve(out.vertices.size() + std::size_t(4 * n) * TileMesh::kFloatsPerVertex);
        out.indices.reserve(out.indices.size() + std::size_t(4 * n) * 6);
        mSkirtIndex.assign(out.surfaceVertexCount, -1);
        auto border = [&](std::uint32_t a, std::uint32_t b) {
            const std::uint32_t pa = surfacePost[a], pb = surfacePost[b];
            const int xa = int(pa % std::uint32_t(mSize)), ya = int(pa / std::uint32_t(mSize));
            const int xb = int(pb % std::uint32_t(mSize)), yb = int(pb / std::uint32_t(mSize));
            return (xa == xb && (xa == 0 || xa == n)) || (ya == yb && (ya == 0 || ya == n));
        };
        // Every border edge belongs to exactly one surface triangle; walking triangles in their
        // counter-clockwise order gives each edge with the outside on its right.
        for (std::uint32_t t = 0; t < out.surfaceIndexCount; t += 3) {
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t u = out.indices[t + std::uint32_t(e)];
                const std::uint32_t v = out.indices[t + std::uint32_t((e + 1) % 3)];
                if (!border(u, v)) continue;
                const std::uint32_t us = skirtVertexFor(out, u, skirtDepth);
                const std::uint32_t vs = skirtVertexFor(out, v, skirtDepth);
                const std::uint32_t quad[6] = {u, vs, v, u, us, vs};
                out.indices.insert(out.indices.end(), quad, quad + 6);
            }
        }
    }
    sortByCell(out, out.surfaceIndexCount, std::uint32_t(out.indices.size()), 6,
               out.skirtCellStart);
    mSurfacePost = nullptr;
}

}  // namespace kiosk::terrain
