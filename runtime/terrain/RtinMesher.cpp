#include "runtime/terrain/RtinMesher.h"

#include "runtime/terrain/RtinExtract.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace kiosk::terrain {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

bool isPowerOfTwo(int v) {
    return v > 0 && (v & (v - 1)) == 0;
}

std::string tileName(const TileId& id) {
    return "tile " + std::to_string(id.level) + "/" + std::to_string(id.column) + "/" +
           std::to_string(id.row);
}

// Twice the signed area of (a, b, p); integer lattice so exact.
inline long long edgeFn(int ax, int ay, int bx, int by, int px, int py) {
    return (long long)(bx - ax) * (py - ay) - (long long)(by - ay) * (px - ax);
}

}  // namespace

MeshParams MeshParams::forTile(const io::TileGrid& grid, const TileId& id,
                               const TerrainOptions& options, double tileError, int tier) {
    MeshParams p;
    if (id.level < 0 || id.level > grid.maxLevel()) return p;
    double x0, y0, x1, y1;
    grid.tileBounds(id, x0, y0, x1, y1);
    const io::TileMatrix& m = grid.levels[std::size_t(id.level)];
    p.originX = x0;
    p.originY = y1;
    p.pixelX = m.pixelXSize;
    p.pixelY = m.pixelYSize;
    p.tolerance = options.tinTolerance(tileError, tier);
    p.skirtDepth = options.skirtDepth(grid, id.level, tileError, tier);
    return p;
}

float RtinMesher::triangleError(int ax, int ay, int bx, int by, int cx, int cy) const {
    // Exact: every post of the triangle (edges included) against the triangle's plane.
    // Martini's midpoint-only error can under-estimate when corrections of several levels add
    // up; the renderer's pixel guarantee needs a true bound.
    const float ha = post(ax, ay), hb = post(bx, by), hc = post(cx, cy);
    if (std::isnan(ha) || std::isnan(hb) || std::isnan(hc)) return kInf;
    const long long area = edgeFn(ax, ay, bx, by, cx, cy);
    if (area == 0) return 0.0f;
    // Plane z = A x + B y + C through the three vertices.
    const double ux = bx - ax, uy = by - ay, uz = double(hb) - ha;
    const double vx = cx - ax, vy = cy - ay, vz = double(hc) - ha;
    const double det = ux * vy - uy * vx;
    const double A = (uz * vy - uy * vz) / det;
    const double B = (ux * vz - uz * vx) / det;
    const double C = ha - A * ax - B * ay;
    // Edges are axis-aligned or diagonal (slope 0 or +-1 in x per row), so a row's span inside
    // the triangle is exact integers; no division in the loop.
    struct Edge {
        int y0, y1, x0, slope;
        bool horizontal;
    } edges[3];
    const int xs[3] = {ax, bx, cx}, ys[3] = {ay, by, cy};
    for (int e = 0; e < 3; ++e) {
        const int px = xs[e], py = ys[e], qx = xs[(e + 1) % 3], qy = ys[(e + 1) % 3];
        Edge& ed = edges[e];
        ed.horizontal = py == qy;
        ed.y0 = std::min(py, qy);
        ed.y1 = std::max(py, qy);
        ed.x0 = py <= qy ? px : qx;  // x at y0
        const int dx = py <= qy ? qx - px : px - qx;
        ed.slope = ed.horizontal ? 0 : (dx > 0 ? 1 : (dx < 0 ? -1 : 0));
    }
    const int y0 = std::min({ay, by, cy}), y1 = std::max({ay, by, cy});
    float err = 0.0f;
    for (int y = y0; y <= y1; ++y) {
        int lo = mSize, hi = -1;
        // A horizontal edge's endpoints are also ends of the two other edges: skip it.
        for (const Edge& ed : edges) {
            if (ed.horizontal || y < ed.y0 || y > ed.y1) continue;
            const int x = ed.x0 + ed.slope * (y - ed.y0);
            lo = std::min(lo, x);
            hi = std::max(hi, x);
        }
        const float* row = mPosts + std::size_t(y) * std::size_t(mSize);
        const double base = B * y + C;
        if (mHasNodata) {
            for (int x = lo; x <= hi; ++x)
                if (std::isnan(row[x])) return kInf;
        }
        // Branch-free so the compiler can vectorise the hot loop.
        double rowErr = 0.0;
        for (int x = lo; x <= hi; ++x) {
            const double d = std::abs(A * x + base - double(row[x]));
            rowErr = d > rowErr ? d : rowErr;
        }
        err = std::max(err, float(rowErr));
        if (err > mTolerance) return err;  // only "above tolerance" matters
    }
    return err;
}

void RtinMesher::computeErrors(int ax, int ay, int bx, int by, int cx, int cy, int depth,
                               int target) {
    // (a, b) is the hypotenuse, c the right angle. Smallest triangles (legs of one post) hold
    // no interior post and are never split.
    if (std::abs(ax - cx) + std::abs(ay - cy) <= 1) return;
    const int mx = (ax + bx) / 2, my = (ay + by) / 2;
    if (depth < target) {
        computeErrors(ax, ay, cx, cy, mx, my, depth + 1, target);
        computeErrors(cx, cy, bx, by, mx, my, depth + 1, target);
        return;
    }
    // Children's slots (their hypotenuse midpoints) when they can split at all. Level-by-level
    // order guarantees those slots are final, including contributions from the triangles across
    // their hypotenuses; so a parent splits whenever any child must, and the two triangles
    // sharing a hypotenuse share one slot and split together: no T-junctions.
    float e = 0.0f;
    if (std::abs(ax - mx) + std::abs(ay - my) > 1) {
        e = std::max(
            e,
            mErrors[std::size_t((ay + cy) / 2) * std::size_t(mSize) + std::size_t((ax + cx) / 2)]);
        e = std::max(
            e,
            mErrors[std::size_t((by + cy) / 2) * std::size_t(mSize) + std::size_t((bx + cx) / 2)]);
    }
    float& slot = mErrors[std::size_t(my) * std::size_t(mSize) + std::size_t(mx)];
    // Slots are only ever compared with this build's tolerance: once one exceeds it, the exact
    // value does not matter and the plane scan (the expensive part) can be skipped.
    if (e <= mTolerance && slot <= mTolerance)
        e = std::max(e, triangleError(ax, ay, bx, by, cx, cy));
    slot = std::max(slot, e);
}

std::uint32_t RtinMesher::vertexFor(int x, int y) {
    const std::size_t p = std::size_t(y) * std::size_t(mSize) + std::size_t(x);
    if (mVertexIndex[p] >= 0) return std::uint32_t(mVertexIndex[p]);
    const auto index = std::uint32_t(mOut->vertices.size() / TileMesh::kFloatsPerVertex);
    mVertexIndex[p] = std::int32_t(index);
    mSurfacePost.push_back(std::uint32_t(p));

    auto finite = [&](int xx, int yy) {
        return xx >= 0 && yy >= 0 && xx < mSize && yy < mSize && !std::isnan(post(xx, yy));
    };
    const double h = post(x, y);
    // Central differences where both neighbours exist, one-sided next to borders and holes.
    auto slope = [&](int dx, int dy, double spacing) {
        const bool fwd = finite(x + dx, y + dy), back = finite(x - dx, y - dy);
        if (fwd && back)
            return (double(post(x + dx, y + dy)) - post(x - dx, y - dy)) / (2 * spacing);
        if (fwd) return (double(post(x + dx, y + dy)) - h) / spacing;
        if (back) return (h - double(post(x - dx, y - dy))) / spacing;
        return 0.0;
    };
    const double dzdx = slope(1, 0, mParams.pixelX);
    const double dzdySouth = slope(0, 1, mParams.pixelY);
    glm::dvec3 n(-dzdx, dzdySouth, 1.0);  // y north = -row direction
    n = glm::normalize(n);

    const float v[TileMesh::kFloatsPerVertex] = {float((x + 0.5) * mParams.pixelX),
                                                 float(-(y + 0.5) * mParams.pixelY),
                                                 float(h),
                                                 float(n.x),
                                                 float(n.y),
                                                 float(n.z)};
    mOut->vertices.insert(mOut->vertices.end(), v, v + TileMesh::kFloatsPerVertex);
    return index;
}

void RtinMesher::emitTriangle(int ax, int ay, int bx, int by, int cx, int cy) {
    if (std::isnan(post(ax, ay)) || std::isnan(post(bx, by)) || std::isnan(post(cx, cy))) return;
    // Counter-clockwise in world (y north) is clockwise in post rows (y down).
    if (edgeFn(ax, ay, bx, by, cx, cy) > 0) {
        std::swap(bx, cx);
        std::swap(by, cy);
    }
    const std::uint32_t ia = vertexFor(ax, ay), ib = vertexFor(bx, by), ic = vertexFor(cx, cy);
    mOut->indices.push_back(ia);
    mOut->indices.push_back(ib);
    mOut->indices.push_back(ic);
}

void RtinMesher::extract(int ax, int ay, int bx, int by, int cx, int cy) {
    rtinExtract(
        ax, ay, bx, by, cx, cy, mCellPosts,
        [this](int mx, int my) {
            return mErrors[std::size_t(my) * std::size_t(mSize) + std::size_t(mx)] > mTolerance;
        },
        [this](int x0, int y0, int x1, int y1, int x2, int y2) {
            emitTriangle(x0, y0, x1, y1, x2, y2);
        });
}

Diagnostics RtinMesher::build(const io::RasterTile& tile, const MeshParams& params, TileMesh& out) {
    Diagnostics diags;
    const int n = tile.postsX - 1;
    if (tile.postsX != tile.postsY || !isPowerOfTwo(n) || n > 4096 ||
        tile.values.size() != std::size_t(tile.postsX) * std::size_t(tile.postsY)) {
        diags.error("TERRAIN_TILE_SHAPE", "", tileName(tile.id),
                    "expected (2^k+1)x(2^k+1) posts, got " + std::to_string(tile.postsX) + "x" +
                        std::to_string(tile.postsY) + " with " +
                        std::to_string(tile.values.size()) + " values");
        return diags;
    }
    if (!(params.pixelX > 0) || !(params.pixelY > 0) || !(params.tolerance >= 0) ||
        !(params.skirtDepth >= 0)) {
        diags.error("TERRAIN_MESH_PARAMS", "", tileName(tile.id),
                    "post spacing must be > 0, tolerance and skirt depth >= 0");
        return diags;
    }
    mPosts = tile.values.data();
    mHasNodata =
        std::any_of(tile.values.begin(), tile.values.end(), [](float v) { return std::isnan(v); });
    mSize = tile.postsX;
    // Exact slot errors need every plane scan to run to the end (no early "above tolerance").
    mTolerance = mExactErrors ? double(kInf) : params.tolerance;
    mParams = params;
    mOut = &out;
    const std::size_t posts = tile.values.size();
    mErrors.assign(posts, 0.0f);
    mVertexIndex.assign(posts, -1);
    mSurfacePost.clear();
    out.id = tile.id;
    out.origin = glm::dvec3(params.originX, params.originY, 0.0);
    out.vertices.clear();
    out.indices.clear();
    out.tolerance = params.tolerance;
    out.skirtDepth = params.skirtDepth;
    out.postSpacing = glm::dvec2(params.pixelX, params.pixelY);
    out.postIntervals = n;

    // Two root triangles share the NW-SE diagonal as hypotenuse.
    // Bottom-up, one depth of the hierarchy at a time (deepest non-trivial depth is 2k - 1).
    int k = 0;
    while ((1 << k) < n) ++k;
    out.cellLevels = std::min(TileMesh::kMaxCellLevels, k);
    out.cellPosts = n >> out.cellLevels;
    mCellPosts = out.cellPosts;
    for (int depth = 2 * k - 1; depth >= 0; --depth) {
        computeErrors(0, 0, n, n, 0, n, 0, depth);
        computeErrors(n, n, 0, 0, n, 0, 0, depth);
    }
    mTolerance = params.tolerance;
    extract(0, 0, n, n, 0, n);
    extract(n, n, 0, 0, n, 0);

    mFinisher.finish(out, mSurfacePost, params.skirtDepth);
    mOut = nullptr;
    mPosts = nullptr;
    return diags;
}

float RtinMesher::maxSplitError() const {
    float e = 0.0f;
    for (float v : mErrors) e = std::max(e, v);
    return e;
}

Result<TileMesh> RtinMesher::build(const io::RasterTile& tile, const MeshParams& params) {
    TileMesh mesh;
    Diagnostics d = build(tile, params, mesh);
    if (d.hasErrors()) return Result<TileMesh>(std::move(d));
    return Result<TileMesh>(std::move(mesh), std::move(d));
}

Result<TileMesh> buildTileMesh(const io::RasterTile& tile, const io::TileGrid& grid,
                               const TerrainOptions& options, RtinMesher& mesher, int tier) {
    if (tile.id.level < 0 || tile.id.level > grid.maxLevel()) {
        Diagnostics d;
        d.error("TERRAIN_TILE_LEVEL", "", tileName(tile.id),
                "level not in the store's tile grid (" + std::to_string(grid.levels.size()) +
                    " levels)");
        return Result<TileMesh>(std::move(d));
    }
    const MeshParams params =
        MeshParams::forTile(grid, tile.id, options, double(tile.stats.geometricError), tier);
    return mesher.build(tile, params);
}

}  // namespace kiosk::terrain
