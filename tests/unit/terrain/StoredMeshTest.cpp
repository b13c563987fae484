// Stored tile meshes (issue 20): the mesh decoded from the store equals the one the loader would
// build from the posts, keeps the error bound (by brute force), and a damaged blob is refused
// with one message naming the tile, never a crash.
#include "runtime/io/MeshBlob.h"
#include "runtime/terrain/RtinMesher.h"
#include "runtime/terrain/StoredMesh.h"
#include "tests/unit/terrain/MeshCheck.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace kiosk::terrain {
namespace {

constexpr double kStep = 0.125;  // the layer's quantisation step (a power of two)

// Rough mountain posts quantised to the step, as the store decodes them; optional nodata hole.
io::RasterTile mountainTile(const TileId& id, bool hole) {
    io::RasterTile t;
    t.id = id;
    t.postsX = t.postsY = 257;
    t.values.resize(257u * 257u);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(0.0, 4.0);
    for (int y = 0; y < 257; ++y)
        for (int x = 0; x < 257; ++x) {
            const double v =
                1500.0 + 400.0 * std::sin(x * 0.03) * std::cos(y * 0.025) + 2.0 * x + noise(rng);
            const bool nodata = hole && x > 40 && x < 70 && y > 100 && y < 140;
            t.values[std::size_t(y) * 257 + std::size_t(x)] =
                nodata ? std::numeric_limits<float>::quiet_NaN()
                       : float(std::round(v / kStep) * kStep);
        }
    t.stats.geometricError = 3.0f;
    return t;
}

io::TileGrid grid() {
    io::TileGrid g;
    g.minX = 500000;
    g.maxY = 5200000;
    g.setPyramid(4, 256, 256, 10.0);
    g.maxX = g.minX + 256 * 8 * 10.0;
    g.minY = g.maxY - 256 * 8 * 10.0;
    return g;
}

std::array<float, 9> corners(const TileMesh& m, std::size_t first) {
    std::array<float, 9> c{};
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a)
            c[std::size_t(k * 3 + a)] =
                m.vertices[std::size_t(m.indices[first + std::size_t(k)]) * 6 + std::size_t(a)];
    // Rotation-invariant: the index codec may start a triangle at another corner.
    std::array<float, 9> best = c;
    for (int r = 1; r < 3; ++r) {
        std::array<float, 9> rot{};
        for (int k = 0; k < 9; ++k) rot[std::size_t(k)] = c[std::size_t((k + 3 * r) % 9)];
        best = std::min(best, rot);
    }
    return best;
}

// Triangles of [begin, end) as a multiset of positions, cell by cell.
std::multiset<std::array<float, 9>> triangles(const TileMesh& m, std::uint32_t begin,
                                              std::uint32_t end, std::size_t group) {
    std::multiset<std::array<float, 9>> out;
    for (std::uint32_t i = begin; i < end; i += std::uint32_t(group)) {
        out.insert(corners(m, i));
        if (group == 6) out.insert(corners(m, i + 3));
    }
    return out;
}

struct Stored {
    TileMesh built, decoded;
    std::vector<std::uint8_t> blob;
    MeshParams params;
};

Stored roundTrip(const io::RasterTile& posts, int tier) {
    const io::TileGrid g = grid();
    TerrainOptions options;
    options.neighbourErrorBound = 6.0;
    Stored s;
    RtinMesher mesher;
    s.params = MeshParams::forTile(g, posts.id, options, posts.stats.geometricError, tier);
    EXPECT_FALSE(mesher.build(posts, s.params, s.built).hasErrors());
    auto q = quantizeSurface(s.built, kStep);
    EXPECT_TRUE(q.ok()) << q.diagnostics.format();
    if (!q.ok()) return s;
    s.blob = io::encodeMeshBlob(*q);
    auto back = io::decodeMeshBlob(s.blob.data(), s.blob.size(), "elevation/3/2/5 tier 0");
    EXPECT_TRUE(back.ok()) << back.diagnostics.format();
    if (!back.ok()) return s;
    StoredMeshBuilder builder;
    const Diagnostics d =
        builder.build(*back, posts.id, g, s.params.tolerance, s.params.skirtDepth, s.decoded);
    EXPECT_FALSE(d.hasErrors()) << d.format();
    return s;
}

TEST(StoredMesh, DecodedMeshEqualsTheMeshBuiltOnLoad) {
    for (bool hole : {false, true})
        for (int tier : {0, 2}) {
            SCOPED_TRACE(std::string(hole ? "with" : "without") + " nodata, tier " +
                         std::to_string(tier));
            const io::RasterTile posts = mountainTile(TileId{3, 2, 5}, hole);
            const Stored s = roundTrip(posts, tier);
            const TileMesh &a = s.built, &b = s.decoded;
            ASSERT_EQ(a.vertexCount(), b.vertexCount());
            ASSERT_EQ(a.surfaceVertexCount, b.surfaceVertexCount);
            ASSERT_EQ(a.surfaceIndexCount, b.surfaceIndexCount);
            ASSERT_EQ(a.indices.size(), b.indices.size());
            EXPECT_EQ(a.origin, b.origin);
            EXPECT_EQ(a.minZ, b.minZ);
            EXPECT_EQ(a.maxZ, b.maxZ);
            EXPECT_EQ(a.cellLevels, b.cellLevels);
            EXPECT_EQ(a.surfaceCellStart, b.surfaceCellStart);
            EXPECT_EQ(a.skirtCellStart, b.skirtCellStart);
            // Positions are exact (heights are whole steps of the layer's quantisation), cell
            // by cell: a finer texture node draws the same part of either mesh.
            for (int c = 0; c < a.cellCount(); ++c) {
                const std::size_t k = std::size_t(c);
                EXPECT_EQ(triangles(a, a.surfaceCellStart[k], a.surfaceCellStart[k + 1], 3),
                          triangles(b, b.surfaceCellStart[k], b.surfaceCellStart[k + 1], 3))
                    << "surface cell " << c;
                EXPECT_EQ(triangles(a, a.skirtCellStart[k], a.skirtCellStart[k + 1], 6),
                          triangles(b, b.skirtCellStart[k], b.skirtCellStart[k + 1], 6))
                    << "skirt cell " << c;
            }
            // Normals: 12-bit octahedral, so within 1e-3 of the built ones (matched by position).
            std::map<std::array<float, 3>, std::array<float, 3>> normals;
            for (std::size_t v = 0; v < a.surfaceVertexCount; ++v)
                normals[{a.vertices[v * 6], a.vertices[v * 6 + 1], a.vertices[v * 6 + 2]}] = {
                    a.vertices[v * 6 + 3], a.vertices[v * 6 + 4], a.vertices[v * 6 + 5]};
            double worst = 0.0;
            for (std::size_t v = 0; v < b.surfaceVertexCount; ++v) {
                const auto it =
                    normals.find({b.vertices[v * 6], b.vertices[v * 6 + 1], b.vertices[v * 6 + 2]});
                ASSERT_NE(it, normals.end()) << "decoded vertex " << v << " not in the built mesh";
                for (int c = 0; c < 3; ++c)
                    worst =
                        std::max(worst, double(std::abs(it->second[std::size_t(c)] -
                                                        b.vertices[v * 6 + 3 + std::size_t(c)])));
            }
            EXPECT_LT(worst, 1e-3);
            // The error bound, by brute force against every post.
            const auto [err, area] = bruteForceError(b, posts, s.params);
            EXPECT_LE(err, s.params.tolerance + 1e-3);
            if (!hole) {
                EXPECT_NEAR(area, 256.0 * 256.0, 1e-6);
            }
            // Compression: well under the 24-byte float vertices plus 4-byte indices.
            EXPECT_LT(s.blob.size() * 4, a.surfaceVertexCount * 24 + a.surfaceIndexCount * 4);
        }
}

TEST(StoredMesh, CoarserTiersDerivedFromTierZeroEqualTheBuiltOnes) {
    // One stored mesh (tier 0 with exact split tiers) gives every tier the loader may ask for:
    // the same triangles in the same order, the same vertex numbering and positions.
    const io::RasterTile posts = mountainTile(TileId{3, 2, 5}, false);
    const io::TileGrid g = grid();
    const TerrainOptions options;
    RtinMesher exact;
    exact.setExactErrors(true);
    TileMesh base;
    const MeshParams p0 = MeshParams::forTile(g, posts.id, options, posts.stats.geometricError, 0);
    ASSERT_FALSE(exact.build(posts, p0, base).hasErrors());
    auto q = quantizeSurface(base, kStep);
    ASSERT_TRUE(q.ok());
    q->splitTiers = splitTiersOf(exact, p0.tolerance);
    const std::vector<std::uint8_t> blob = io::encodeMeshBlob(*q);
    auto stored = io::decodeMeshBlob(blob.data(), blob.size(), "elevation/3/2/5 tier 0");
    ASSERT_TRUE(stored.ok()) << stored.diagnostics.format();
    ASSERT_EQ(stored->splitTiers.size(), stored->vertexCount());
    RtinMesher mesher;  // the loader's: tolerance-limited errors
    StoredMeshBuilder builder;
    std::size_t previous = base.triangleCount() + 1;
    for (int tier = 1; tier <= options.maxToleranceTier(); ++tier) {
        SCOPED_TRACE("tier " + std::to_string(tier));
        const MeshParams p =
            MeshParams::forTile(g, posts.id, options, posts.stats.geometricError, tier);
        TileMesh built, derived;
        ASSERT_FALSE(mesher.build(posts, p, built).hasErrors());
        ASSERT_FALSE(builder.derive(*stored, tier, posts.id, g, p.tolerance, p.skirtDepth, derived)
                         .hasErrors());
        EXPECT_EQ(built.indices, derived.indices);
        ASSERT_EQ(built.vertices.size(), derived.vertices.size());
        double worstNormal = 0.0;
        for (std::size_t i = 0; i < built.vertices.size(); ++i) {
            if (i % 6 < 3)
                ASSERT_EQ(built.vertices[i], derived.vertices[i]) << "float " << i;
            else
                worstNormal = std::max(worstNormal,
                                       double(std::abs(built.vertices[i] - derived.vertices[i])));
        }
        EXPECT_LT(worstNormal, 1e-3);
        EXPECT_EQ(built.surfaceCellStart, derived.surfaceCellStart);
        EXPECT_EQ(built.skirtCellStart, derived.skirtCellStart);
        EXPECT_LE(bruteForceError(derived, posts, p).first, p.tolerance + 1e-3);
        EXPECT_LE(derived.triangleCount(), previous);
        previous = derived.triangleCount();
    }
    EXPECT_LT(previous, base.triangleCount() / 4);  // the tiers do coarsen
}

TEST(StoredMesh, HeightsOffTheStepAreRefused) {
    io::RasterTile posts = mountainTile(TileId{3, 2, 5}, false);
    posts.values[1000] += 0.01f;  // not a multiple of 1/8 any more
    RtinMesher mesher;
    TileMesh mesh;
    MeshParams p = MeshParams::forTile(grid(), posts.id, TerrainOptions{}, 0.0, 0);
    p.tolerance = 0.0;  // keep every post, the odd one included
    ASSERT_FALSE(mesher.build(posts, p, mesh).hasErrors());
    auto q = quantizeSurface(mesh, kStep);
    ASSERT_FALSE(q.ok());
    EXPECT_TRUE(q.diagnostics.has("TERRAIN_MESH_QUANTISE"));
    EXPECT_NE(q.diagnostics.format().find("tile 3/2/5"), std::string::npos);
}

TEST(StoredMesh, DamagedBlobsAreOneClearErrorNeverACrash) {
    const Stored s = roundTrip(mountainTile(TileId{3, 2, 5}, false), 0);
    ASSERT_FALSE(s.blob.empty());
    const std::string where = "elevation/3/2/5 tier 0";
    auto expectRefused = [&](std::vector<std::uint8_t> blob, const char* what) {
        auto r = io::decodeMeshBlob(blob.data(), blob.size(), where);
        ASSERT_FALSE(r.ok()) << what;
        ASSERT_EQ(r.diagnostics.size(), 1u) << what;
        EXPECT_EQ(r.diagnostics.items()[0].code, "STORE_MESH_CORRUPT") << what;
        EXPECT_EQ(r.diagnostics.items()[0].where, where) << what;
    };
    expectRefused({}, "empty");
    expectRefused(std::vector<std::uint8_t>(s.blob.begin(), s.blob.begin() + 30), "short");
    expectRefused(std::vector<std::uint8_t>(s.blob.begin(), s.blob.end() - 7), "truncated");
    std::vector<std::uint8_t> b = s.blob;
    b[0] = 'X';
    expectRefused(b, "magic");
    b = s.blob;
    b[13] = 0xFF;  // vertex count far beyond a 257x257 grid
    expectRefused(b, "vertex count");
    b = s.blob;
    b[17] = 0x7F;  // index count
    expectRefused(b, "index count");
    // Random damage anywhere: decoded or refused, in bounds (ASan/UBSan builds check that).
    std::mt19937 rng(11);
    int refused = 0;
    for (int i = 0; i < 300; ++i) {
        b = s.blob;
        for (int k = 0; k < 4; ++k) b[rng() % b.size()] ^= std::uint8_t(1u + rng() % 255u);
        auto r = io::decodeMeshBlob(b.data(), b.size(), where);
        if (!r.ok()) {
            ++refused;
            EXPECT_TRUE(r.diagnostics.has("STORE_MESH_CORRUPT"));
            continue;
        }
        // What decodes is still a mesh on the tile's grid the builder accepts or refuses.
        TileMesh m;
        StoredMeshBuilder builder;
        (void)builder.build(*r, TileId{3, 2, 5}, grid(), 1.0, 5.0, m);
    }
    EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace kiosk::terrain
