#include "runtime/terrain/StoredMesh.h"

#include "runtime/terrain/RtinExtract.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace kiosk::terrain {

namespace {

std::string tileName(const TileId& id) {
    return "tile " + std::to_string(id.level) + "/" + std::to_string(id.column) + "/" +
           std::to_string(id.row);
}

}  // namespace

Result<io::QuantizedMesh> quantizeSurface(const TileMesh& mesh, double zStep) {
    Diagnostics d;
    auto fail = [&](const std::string& what) {
        d.error("TERRAIN_MESH_QUANTISE", "", tileName(mesh.id), what);
        return Result<io::QuantizedMesh>(std::move(d));
    };
    if (!(zStep > 0) || mesh.postIntervals < 1 || mesh.postIntervals > 65535)
        return fail("no height step or post grid to quantise to");
    io::QuantizedMesh q;
    q.postIntervals = mesh.postIntervals;
    q.zOffset = double(mesh.minZ);
    q.zScale = zStep;
    const std::size_t count = mesh.surfaceVertexCount;
    q.posts.resize(count * 3);
    q.normals.resize(count * 3);
    const double px = mesh.postSpacing.x, py = mesh.postSpacing.y;
    for (std::size_t v = 0; v < count; ++v) {
        const float* f = &mesh.vertices[v * TileMesh::kFloatsPerVertex];
        const double col = std::round(f[0] / px - 0.5), row = std::round(-f[1] / py - 0.5);
        const double h = std::round((double(f[2]) - q.zOffset) / zStep);
        if (col < 0 || row < 0 || col > mesh.postIntervals || row > mesh.postIntervals ||
            float((col + 0.5) * px) != f[0] || float(-(row + 0.5) * py) != f[1])
            return fail("vertex " + std::to_string(v) + " is not on the post grid");
        if (h < 0 || h > 65535 || float(q.zOffset + h * zStep) != f[2])
            return fail("height " + std::to_string(f[2]) + " is not a multiple of the step " +
                        std::to_string(zStep) + " within 65535 steps of the tile's lowest");
        q.posts[v * 3] = std::uint16_t(col);
        q.posts[v * 3 + 1] = std::uint16_t(row);
        q.posts[v * 3 + 2] = std::uint16_t(h);
        for (int c = 0; c < 3; ++c) q.normals[v * 3 + std::size_t(c)] = f[3 + c];
    }
    q.indices.assign(mesh.indices.begin(), mesh.indices.begin() + mesh.surfaceIndexCount);
    return q;
}

std::vector<std::uint16_t> splitTiersOf(const RtinMesher& mesher, double tolerance) {
    std::vector<std::uint16_t> tiers;
    tiers.reserve(mesher.surfacePosts().size());
    for (const std::uint32_t post : mesher.surfacePosts()) {
        // The mesher splits at a midpoint while error > tolerance (float against double).
        const double e = double(mesher.slotError(post));
        std::uint16_t k = 0;
        while (k <= 30 && e > std::ldexp(tolerance, k)) ++k;
        tiers.push_back(k > 30 ? std::uint16_t(0xFFFF) : k);
    }
    return tiers;
}

Diagnostics StoredMeshBuilder::begin(const io::QuantizedMesh& stored, const TileId& id,
                                     const io::TileGrid& grid, double tolerance, TileMesh& out) {
    Diagnostics d;
    if (id.level < 0 || id.level > grid.maxLevel()) {
        d.error("TERRAIN_TILE_LEVEL", "", tileName(id), "level not in the store's tile grid");
        return d;
    }
    const io::TileMatrix& m = grid.levels[std::size_t(id.level)];
    const int n = stored.postIntervals;
    if (n != m.tileWidth || n != m.tileHeight) {
        d.error("STORE_MESH_CORRUPT", "", tileName(id),
                "stored mesh has " + std::to_string(n) + " post intervals, the level's tiles " +
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
    int k = 0;
    while ((1 << k) < n) ++k;
    out.cellLevels = std::min(TileMesh::kMaxCellLevels, k);
    out.cellPosts = std::max(1, n >> out.cellLevels);
    return d;
}

Diagnostics StoredMeshBuilder::build(const io::QuantizedMesh& stored, const TileId& id,
                                     const io::TileGrid& grid, double tolerance, double skirtDepth,
                                     TileMesh& out) {
    Diagnostics d = begin(stored, id, grid, tolerance, out);
    if (d.hasErrors()) return d;
    const io::TileMatrix& m = grid.levels[std::size_t(id.level)];
    const int n = stored.postIntervals;
    // The same float expressions as RtinMesher::vertexFor: identical positions.
    const std::size_t count = stored.vertexCount();
    out.vertices.reserve((count + std::size_t(4 * n)) * TileMesh::kFloatsPerVertex);
    out.vertices.resize(count * TileMesh::kFloatsPerVertex);
    mSurfacePost.resize(count);
    for (std::size_t v = 0; v < count; ++v) {
        const int x = stored.posts[v * 3], y = stored.posts[v * 3 + 1];
        float* f = &out.vertices[v * TileMesh::kFloatsPerVertex];
        f[0] = float((x + 0.5) * m.pixelXSize);
        f[1] = float(-(y + 0.5) * m.pixelYSize);
        f[2] = float(stored.zOffset + double(stored.posts[v * 3 + 2]) * stored.zScale);
        for (int c = 0; c < 3; ++c) f[3 + c] = stored.normals[v * 3 + std::size_t(c)];
        mSurfacePost[v] = std::uint32_t(y) * std::uint32_t(n + 1) + std::uint32_t(x);
    }
    // Cell ranges are what lets finer texture nodes draw a part of this mesh: a triangle that
    // crosses a cell border would be drawn by the wrong node.
    const int cp = out.cellPosts;
    for (std::size_t t = 0; t < stored.indices.size(); t += 3) {
        int lo[2] = {n, n}, hi[2] = {0, 0};
        for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 2; ++a) {
                const int p = stored.posts[std::size_t(stored.indices[t + std::size_t(c)]) * 3 +
                                           std::size_t(a)];
                lo[a] = std::min(lo[a], p);
                hi[a] = std::max(hi[a], p);
            }
        if (hi[0] > (lo[0] / cp + 1) * cp || hi[1] > (lo[1] / cp + 1) * cp) {
            d.error("STORE_MESH_CORRUPT", "", tileName(id),
                    "stored mesh has a triangle across "
                    "cells");
            return d;
        }
    }
    out.indices.reserve(stored.indices.size() + std::size_t(4 * n) * 6);
    out.indices.assign(stored.indices.begin(), stored.indices.end());
    mFinisher.finish(out, mSurfacePost, skirtDepth);
    return d;
}

std::uint32_t StoredMeshBuilder::vertexFor(int x, int y) {
    const std::size_t p = std::size_t(y) * std::size_t(mSize) + std::size_t(x);
    const std::size_t v = std::size_t(mPostVertex[p]);
    if (mOutIndex[v] >= 0) return std::uint32_t(mOutIndex[v]);
    const auto index = std::uint32_t(mOut->vertexCount());
    mOutIndex[v] = std::int32_t(index);
    mSurfacePost.push_back(std::uint32_t(p));
    const io::QuantizedMesh& s = *mStored;
    const float f[TileMesh::kFloatsPerVertex] = {
        float((x + 0.5) * mOut->postSpacing.x),
        float(-(y + 0.5) * mOut->postSpacing.y),
        float(s.zOffset + double(s.posts[v * 3 + 2]) * s.zScale),
        s.normals[v * 3],
        s.normals[v * 3 + 1],
        s.normals[v * 3 + 2]};
    mOut->vertices.insert(mOut->vertices.end(), f, f + TileMesh::kFloatsPerVertex);
    return index;
}

// RtinMesher::extract and emitTriangle with the split decision read from the stored tiers:
// the same recursion, so the same triangles in the same order with the same vertex numbering.
void StoredMeshBuilder::extract(int ax, int ay, int bx, int by, int cx, int cy) {
    auto stored = [&](int x, int y) {
        return mPostVertex[std::size_t(y) * std::size_t(mSize) + std::size_t(x)] >= 0;
    };
    auto split = [&](int mx, int my) {
        return mPostTier[std::size_t(my) * std::size_t(mSize) + std::size_t(mx)] > mTier;
    };
    auto emit = [&](int x0, int y0, int x1, int y1, int x2, int y2) {
        if (!stored(x0, y0) || !stored(x1, y1) || !stored(x2, y2)) return;  // nodata
        // Counter-clockwise in world (y north) is clockwise in post rows (y down).
        if ((long long)(x1 - x0) * (y2 - y0) - (long long)(y1 - y0) * (x2 - x0) > 0) {
            std::swap(x1, x2);
            std::swap(y1, y2);
        }
        const std::uint32_t i0 = vertexFor(x0, y0), i1 = vertexFor(x1, y1);
        const std::uint32_t i2 = vertexFor(x2, y2);
        mOut->indices.insert(mOut->indices.end(), {i0, i1, i2});
    };
    rtinExtract(ax, ay, bx, by, cx, cy, mCellPosts, split, emit);
}

Diagnostics StoredMeshBuilder::derive(const io::QuantizedMesh& stored, int tier, const TileId& id,
                                      const io::TileGrid& grid, double tolerance, double skirtDepth,
                                      TileMesh& out) {
    Diagnostics d = begin(stored, id, grid, tolerance, out);
    if (d.hasErrors()) return d;
    if (stored.splitTiers.size() != stored.vertexCount()) {
        d.error("STORE_MESH_CORRUPT", "", tileName(id), "stored mesh has no split tiers");
        return d;
    }
    const int n = stored.postIntervals;
    mSize = n + 1;
    mTier = tier;
    mCellPosts = out.cellPosts;
    mStored = &stored;
    mOut = &out;
    const std::size_t posts = std::size_t(mSize) * std::size_t(mSize);
    mPostVertex.assign(posts, -1);
    mPostTier.assign(posts, 0);
    mOutIndex.assign(stored.vertexCount(), -1);
    for (std::size_t v = 0; v < stored.vertexCount(); ++v) {
        const std::size_t p =
            std::size_t(stored.posts[v * 3 + 1]) * std::size_t(mSize) + stored.posts[v * 3];
        mPostVertex[p] = std::int32_t(v);
        mPostTier[p] = stored.splitTiers[v];
    }
    out.vertices.clear();
    out.indices.clear();
    // Upper bounds (a coarser tier has no more vertices or triangles than tier 0; skirts add
    // at most a vertex per border post and a quad per border edge): one allocation each.
    out.vertices.reserve((stored.vertexCount() + std::size_t(4 * n)) * TileMesh::kFloatsPerVertex);
    out.indices.reserve(stored.indices.size() + std::size_t(4 * n) * 6);
    mSurfacePost.clear();
    extract(0, 0, n, n, 0, n);
    extract(n, n, 0, 0, n, 0);
    mFinisher.finish(out, mSurfacePost, skirtDepth);
    // The reserve was tier 0's size; a coarse tier keeps a fraction of it, and the payload waits
    // in the loader's ring and the cache until uploaded: give the rest back (one small copy).
    if (out.vertices.capacity() > out.vertices.size() + out.vertices.size() / 4)
        out.vertices.shrink_to_fit();
    if (out.indices.capacity() > out.indices.size() + out.indices.size() / 4)
        out.indices.shrink_to_fit();
    mStored = nullptr;
    mOut = nullptr;
    return d;
}

}  // namespace kiosk::terrain
