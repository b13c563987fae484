#include "runtime/terrain/MeshCells.h"
#include "runtime/terrain/RtinMesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace kiosk::terrain {
namespace {

io::RasterTile roughTile(int posts) {
    io::RasterTile t;
    t.id = TileId{2, 1, 1};
    t.postsX = t.postsY = posts;
    t.values.resize(std::size_t(posts) * std::size_t(posts));
    for (int y = 0; y < posts; ++y)
        for (int x = 0; x < posts; ++x)
            t.values[std::size_t(y * posts + x)] =
                float(300.0 + 80.0 * std::sin(x * 0.09) * std::cos(y * 0.07) +
                      5.0 * std::sin(x * y * 0.01));
    return t;
}

MeshParams params(double tolerance) {
    MeshParams p;
    p.originX = 10000.0;
    p.originY = 50000.0;
    p.pixelX = 4.0;
    p.pixelY = 4.0;
    p.tolerance = tolerance;
    p.skirtDepth = 20.0;
    return p;
}

glm::dvec2 vertexXY(const TileMesh& m, std::uint32_t v) {
    const float* f = &m.vertices[std::size_t(v) * TileMesh::kFloatsPerVertex];
    return {m.origin.x + double(f[0]), m.origin.y + double(f[1])};
}

TEST(MeshCells, MortonCodeOrdersQuadrantsContiguously) {
    std::vector<int> seen(64, 0);
    for (std::uint32_t y = 0; y < 8; ++y)
        for (std::uint32_t x = 0; x < 8; ++x) {
            const std::uint32_t c = cellMortonCode(x, y);
            ASSERT_LT(c, 64u);
            ++seen[c];
            // The quadrant (x / 4, y / 4) owns codes [16 q, 16 q + 16), q = 2 (y/4) + x/4.
            EXPECT_EQ(c / 16, 2 * (y / 4) + x / 4) << x << "," << y;
            EXPECT_EQ((c % 16) / 4, 2 * ((y / 2) % 2) + (x / 2) % 2) << x << "," << y;
        }
    for (int n : seen) EXPECT_EQ(n, 1);  // a bijection
    EXPECT_EQ(cellMortonCode(1, 0), 1u);
    EXPECT_EQ(cellMortonCode(0, 1), 2u);
    EXPECT_EQ(cellMortonCode(7, 7), 63u);
}

TEST(MeshCells, CellRangesCoverEveryTriangleOnceAndHoldOnlyTheirCell) {
    RtinMesher mesher;
    for (double tol : {0.0, 0.5, 5.0, 40.0}) {
        auto mesh = mesher.build(roughTile(257), params(tol));
        ASSERT_TRUE(mesh.ok());
        const TileMesh& m = *mesh;
        ASSERT_EQ(m.cellLevels, 3);
        // Surface ranges tile [0, surfaceIndexCount), skirts [surfaceIndexCount, end).
        EXPECT_EQ(m.surfaceCellStart[0], 0u);
        EXPECT_EQ(m.surfaceCellStart[64], m.surfaceIndexCount);
        EXPECT_EQ(m.skirtCellStart[0], m.surfaceIndexCount);
        EXPECT_EQ(m.skirtCellStart[64], m.indices.size());
        std::vector<int> covered(m.indices.size() / 3, 0);
        for (int section = 0; section < 2; ++section) {
            const auto& starts = section == 0 ? m.surfaceCellStart : m.skirtCellStart;
            for (std::uint32_t y = 0; y < 8; ++y)
                for (std::uint32_t x = 0; x < 8; ++x) {
                    const std::uint32_t c = cellMortonCode(x, y);
                    ASSERT_LE(starts[c], starts[c + 1]);
                    ASSERT_EQ(starts[c] % 3, 0u);
                    glm::dvec2 lo, hi;
                    meshCellBounds(m, int(x), int(y), lo, hi);
                    for (std::uint32_t i = starts[c]; i < starts[c + 1]; i += 3) {
                        ++covered[i / 3];
                        for (int k = 0; k < 3; ++k) {
                            const glm::dvec2 p = vertexXY(m, m.indices[i + std::uint32_t(k)]);
                            EXPECT_GE(p.x, lo.x - 1e-3) << "cell " << x << "," << y;
                            EXPECT_LE(p.x, hi.x + 1e-3) << "cell " << x << "," << y;
                            EXPECT_GE(p.y, lo.y - 1e-3) << "cell " << x << "," << y;
                            EXPECT_LE(p.y, hi.y + 1e-3) << "cell " << x << "," << y;
                        }
                    }
                }
        }
        for (std::size_t t = 0; t < covered.size(); ++t)
            ASSERT_EQ(covered[t], 1) << "triangle " << t << " at tolerance " << tol;
        // Border cells own skirts, interior cells none.
        EXPECT_GT(m.skirtCellStart[cellMortonCode(0, 3) + 1],
                  m.skirtCellStart[cellMortonCode(0, 3)]);
        EXPECT_EQ(m.skirtCellStart[cellMortonCode(3, 3) + 1],
                  m.skirtCellStart[cellMortonCode(3, 3)]);
    }
}

// A descendant's rectangle (as the selector clips it) must get every triangle that has a
// fragment inside it, and for an aligned quadrant no more than its own cells plus the one-post
// sliver the pixel-centred posts leave.
TEST(MeshCells, RangesInRectKeepEveryTriangleTouchingTheRect) {
    RtinMesher mesher;
    auto mesh = mesher.build(roughTile(257), params(0.5));
    ASSERT_TRUE(mesh.ok());
    const TileMesh& m = *mesh;
    const double px = 4.0, tile = 256 * px;  // the tile spans [x0, x0 + tile] x [y1 - tile, y1]
    const double x0 = m.origin.x, y1 = m.origin.y;
    std::vector<IndexRange> ranges;
    struct Case {
        int level;  // levels below the mesh's tile
        int col, row;
    };
    for (const Case c : {Case{1, 0, 0}, Case{1, 1, 0}, Case{1, 0, 1}, Case{1, 1, 1}, Case{2, 2, 1},
                         Case{3, 7, 7}, Case{4, 5, 9}, Case{5, 0, 31}}) {
        const double size = tile / double(1 << c.level), childPx = px / double(1 << c.level);
        // Node's mesh domain (its posts) grown by a quarter of its post, as TerrainScene clips.
        const glm::dvec2 lo(x0 + c.col * size + 0.25 * childPx,
                            y1 - (c.row + 1) * size - 0.75 * childPx);
        const glm::dvec2 hi(x0 + (c.col + 1) * size + 0.75 * childPx,
                            y1 - c.row * size - 0.25 * childPx);
        ASSERT_TRUE(meshRangesInRect(m, lo, hi, ranges));
        std::vector<char> drawn(m.indices.size() / 3, 0);
        std::uint32_t last = 0;
        for (const IndexRange& r : ranges) {
            EXPECT_GE(r.first, last) << "ranges sorted and disjoint";
            EXPECT_GT(r.count, 0u);
            EXPECT_EQ(r.count % 3, 0u);
            last = r.first + r.count;
            for (std::uint32_t i = r.first; i < r.first + r.count; i += 3) drawn[i / 3] = 1;
        }
        std::size_t kept = 0;
        for (std::size_t t = 0; t < drawn.size(); ++t) {
            kept += std::size_t(drawn[t]);
            // Triangle bounding box against the rectangle: any overlap must be drawn.
            glm::dvec2 bmin(1e300), bmax(-1e300);
            for (int k = 0; k < 3; ++k) {
                const glm::dvec2 p = vertexXY(m, m.indices[t * 3 + std::size_t(k)]);
                bmin = glm::min(bmin, p);
                bmax = glm::max(bmax, p);
            }
            const bool overlaps = bmax.x > lo.x && bmin.x < hi.x && bmax.y > lo.y && bmin.y < hi.y;
            if (overlaps) {
                EXPECT_TRUE(drawn[t]) << "level " << c.level << " triangle " << t;
            }
        }
        if (c.level == 1) {
            // A quadrant of 16 cells, at most 9 more cells of sliver: well under half the mesh
            // for the NW quadrant (no sliver), under 0.7 for the others.
            const double share = double(kept) / double(drawn.size());
            EXPECT_LT(share, c.col == 0 && c.row == 0 ? 0.45 : 0.7) << c.col << "," << c.row;
            EXPECT_GT(share, 0.1);
        }
    }
    // The whole tile's rectangle keeps everything in one run.
    ASSERT_TRUE(meshRangesInRect(m, glm::dvec2(x0 - 10, y1 - tile - 10),
                                 glm::dvec2(x0 + tile + 10, y1 + 10), ranges));
    ASSERT_EQ(ranges.size(), 1u);
    EXPECT_EQ(ranges[0].first, 0u);
    EXPECT_EQ(ranges[0].count, m.indices.size());
    // A rectangle away from the tile keeps nothing; a mesh without cells reports false.
    ASSERT_TRUE(
        meshRangesInRect(m, glm::dvec2(x0 + 2 * tile), glm::dvec2(x0 + 3 * tile, y1), ranges));
    EXPECT_TRUE(ranges.empty());
    TileMesh plain;
    EXPECT_FALSE(meshRangesInRect(plain, glm::dvec2(0), glm::dvec2(1), ranges));
}

}  // namespace
}  // namespace kiosk::terrain
