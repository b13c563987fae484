#include "runtime/terrain/RtinMesher.h"
#include "tests/unit/terrain/MeshCheck.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <utility>

namespace kiosk::terrain {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

io::RasterTile makeTile(int posts, const std::function<float(int, int)>& f) {
    io::RasterTile t;
    t.id = TileId{3, 2, 5};
    t.postsX = t.postsY = posts;
    t.values.resize(std::size_t(posts) * std::size_t(posts));
    for (int y = 0; y < posts; ++y)
        for (int x = 0; x < posts; ++x) t.values[std::size_t(y * posts + x)] = f(x, y);
    return t;
}

// Deterministic rough terrain: ridges plus hashed noise of a few metres.
float rough(int x, int y) {
    std::uint32_t h = std::uint32_t(x) * 73856093u ^ std::uint32_t(y) * 19349663u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    const double noise = double(h % 1000u) / 1000.0 * 3.0;
    return float(200.0 + 60.0 * std::sin(x * 0.05) * std::cos(y * 0.04) + 0.3 * x + noise);
}

MeshParams params(double tolerance, double skirt = 10.0) {
    MeshParams p;
    p.originX = 1000.0;
    p.originY = 5000.0;
    p.pixelX = 2.0;
    p.pixelY = 3.0;
    p.tolerance = tolerance;
    p.skirtDepth = skirt;
    return p;
}

TEST(RtinMesher, ErrorBoundHoldsByBruteForce) {
    const io::RasterTile tile = makeTile(129, rough);
    RtinMesher mesher;
    for (double tol : {0.0, 0.5, 2.0, 8.0, 40.0}) {
        SCOPED_TRACE("tolerance " + std::to_string(tol));
        const MeshParams p = params(tol);
        auto mesh = mesher.build(tile, p);
        ASSERT_TRUE(mesh.ok()) << mesh.diagnostics.format();
        const auto [err, area] = bruteForceError(*mesh, tile, p);
        EXPECT_LE(err, tol + 1e-3);
        EXPECT_NEAR(area, 128.0 * 128.0, 1e-6);  // every cell covered, nothing twice
    }
}

// Strictly convex: no post lies on a plane through others, so nothing can be dropped exactly.
float bowl(int x, int y) {
    return float(0.01 * (x * x + 1.3 * y * y));
}

TEST(RtinMesher, ZeroToleranceOnFullTileKeepsEveryPost) {
    const io::RasterTile tile = makeTile(257, bowl);
    RtinMesher mesher;
    auto mesh = mesher.build(tile, params(0.0));
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(mesh->surfaceVertexCount, 257u * 257u);
    EXPECT_EQ(mesh->surfaceTriangleCount(), 2u * 256u * 256u);
}

TEST(RtinMesher, TriangleCountDropsWithTolerance) {
    const io::RasterTile tile = makeTile(257, rough);
    RtinMesher mesher;
    std::size_t previous = std::numeric_limits<std::size_t>::max();
    for (double tol : {0.0, 1.0, 4.0, 16.0, 64.0}) {
        auto mesh = mesher.build(tile, params(tol));
        ASSERT_TRUE(mesh.ok());
        EXPECT_LT(mesh->surfaceTriangleCount(), previous) << "tolerance " << tol;
        previous = mesh->surfaceTriangleCount();
    }
    EXPECT_LT(previous, 2000u);  // 64 m on 60 m ridges: a handful of triangles
}

TEST(RtinMesher, FlatAndPlanarTilesGiveTwoTrianglesPerCell) {
    // Triangles never span cells (8x8 per tile, so that a quadrant is an index range): a flat
    // tile is one triangle pair per cell, with one skirt quad per border cell edge.
    RtinMesher mesher;
    for (auto f : std::initializer_list<std::function<float(int, int)>>{
             [](int, int) { return 12.5f; },
             [](int x, int y) { return float(100 + 0.25 * x - 0.5 * y); }}) {
        const io::RasterTile tile = makeTile(257, f);
        auto mesh = mesher.build(tile, params(0.0, 5.0));
        ASSERT_TRUE(mesh.ok());
        EXPECT_EQ(mesh->cellLevels, 3);
        EXPECT_EQ(mesh->cellPosts, 32);
        EXPECT_EQ(mesh->surfaceTriangleCount(), 2u * 64u);
        EXPECT_EQ(mesh->surfaceVertexCount, 9u * 9u);
        EXPECT_EQ(mesh->skirtTriangleCount(), 2u * 4u * 8u);  // one quad per border cell edge
        EXPECT_EQ(mesh->vertexCount(), 81u + 32u);
    }
    // A tile smaller than 8 post intervals has as many cells as it has intervals.
    auto small = mesher.build(makeTile(3, [](int, int) { return 1.0f; }), params(0.0, 5.0));
    ASSERT_TRUE(small.ok());
    EXPECT_EQ(small->cellLevels, 1);
    EXPECT_EQ(small->surfaceTriangleCount(), 8u);
}

TEST(RtinMesher, MeshIsConformingAndCounterClockwise) {
    const io::RasterTile tile = makeTile(65, rough);
    RtinMesher mesher;
    const MeshParams p = params(1.5);
    auto mesh = mesher.build(tile, p);
    ASSERT_TRUE(mesh.ok());
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (std::uint32_t i = 0; i < mesh->surfaceIndexCount; i += 3) {
        const float* a = &mesh->vertices[mesh->indices[i] * 6u];
        const float* b = &mesh->vertices[mesh->indices[i + 1] * 6u];
        const float* c = &mesh->vertices[mesh->indices[i + 2] * 6u];
        const double cross =
            double(b[0] - a[0]) * (c[1] - a[1]) - double(b[1] - a[1]) * (c[0] - a[0]);
        EXPECT_GT(cross, 0.0) << "triangle " << i / 3 << " is not counter-clockwise";
        for (int e = 0; e < 3; ++e) {
            std::uint32_t u = mesh->indices[i + std::uint32_t(e)];
            std::uint32_t v = mesh->indices[i + std::uint32_t((e + 1) % 3)];
            ++edges[{std::min(u, v), std::max(u, v)}];
        }
    }
    for (const auto& [e, count] : edges) {
        const PostPos a = toPost(*mesh, e.first, p), b = toPost(*mesh, e.second, p);
        const bool onBorder =
            (std::abs(a.x - b.x) < 1e-6 && (std::abs(a.x) < 1e-6 || std::abs(a.x - 64) < 1e-6)) ||
            (std::abs(a.y - b.y) < 1e-6 && (std::abs(a.y) < 1e-6 || std::abs(a.y - 64) < 1e-6));
        // A T-junction would leave an interior edge with a single triangle.
        EXPECT_EQ(count, onBorder ? 1 : 2)
            << "edge (" << a.x << "," << a.y << ")-(" << b.x << "," << b.y << ")";
    }
}

TEST(RtinMesher, SkirtsHangOnAllFourBordersAndFlareHalfAPost) {
    const io::RasterTile tile = makeTile(65, rough);
    RtinMesher mesher;
    const MeshParams p = params(2.0, 25.0);
    auto mesh = mesher.build(tile, p);
    ASSERT_TRUE(mesh.ok());
    ASSERT_GT(mesh->vertexCount(), mesh->surfaceVertexCount);
    // Border length covered by skirts, per side (in post units): west, east, north, south.
    double covered[4] = {0, 0, 0, 0};
    for (std::uint32_t i = mesh->surfaceIndexCount; i < mesh->indices.size(); i += 6) {
        const std::uint32_t u = mesh->indices[i], v = mesh->indices[i + 2];
        ASSERT_LT(u, mesh->surfaceVertexCount);
        ASSERT_LT(v, mesh->surfaceVertexCount);
        const std::uint32_t ub = mesh->indices[i + 4];
        ASSERT_GE(ub, mesh->surfaceVertexCount);
        const float* top = &mesh->vertices[u * 6u];
        const float* bottom = &mesh->vertices[ub * 6u];
        EXPECT_NEAR(top[2] - bottom[2], 25.0, 1e-3);
        const PostPos a = toPost(*mesh, u, p), b = toPost(*mesh, v, p);
        const double len = std::abs(a.x - b.x) + std::abs(a.y - b.y);
        if (std::abs(a.x) < 1e-6 && std::abs(b.x) < 1e-6) {
            covered[0] += len;
            EXPECT_NEAR(bottom[0], 0.0, 1e-4);  // west skirt bottom on the tile edge
        } else if (std::abs(a.x - 64) < 1e-6 && std::abs(b.x - 64) < 1e-6) {
            covered[1] += len;
            EXPECT_NEAR(bottom[0], 65 * p.pixelX, 1e-3);
        } else if (std::abs(a.y) < 1e-6 && std::abs(b.y) < 1e-6) {
            covered[2] += len;
            EXPECT_NEAR(bottom[1], 0.0, 1e-4);
        } else if (std::abs(a.y - 64) < 1e-6 && std::abs(b.y - 64) < 1e-6) {
            covered[3] += len;
            EXPECT_NEAR(bottom[1], -65 * p.pixelY, 1e-3);
        } else {
            ADD_FAILURE() << "skirt on a non-border edge";
        }
    }
    for (double c : covered) EXPECT_NEAR(c, 64.0, 1e-6);
}

TEST(RtinMesher, NodataMakesHolesWithoutNaNVerticesOrSkirts) {
    // A hole in the middle and the whole west border strip missing.
    io::RasterTile tile = makeTile(65, [](int x, int y) {
        if ((x > 20 && x < 30 && y > 20 && y < 30) || x < 3) return kNaN;
        return rough(x, y);
    });
    RtinMesher mesher;
    const MeshParams p = params(1.0, 10.0);
    auto mesh = mesher.build(tile, p);
    ASSERT_TRUE(mesh.ok()) << mesh.diagnostics.format();
    for (float f : mesh->vertices) ASSERT_TRUE(std::isfinite(f));
    for (std::uint32_t i = 0; i < mesh->surfaceIndexCount; ++i) {
        const PostPos q = toPost(*mesh, mesh->indices[i], p);
        const int x = int(std::lround(q.x)), y = int(std::lround(q.y));
        ASSERT_FALSE(std::isnan(tile.at(x, y)));
    }
    for (std::uint32_t i = mesh->surfaceIndexCount; i < mesh->indices.size(); ++i) {
        const PostPos q = toPost(*mesh, mesh->indices[i], p);
        EXPECT_GT(q.x, 2.0 - 0.51) << "skirt emitted along the nodata border";
    }
    const auto [err, area] = bruteForceError(*mesh, tile, p);
    EXPECT_LE(err, 1.0 + 1e-3);
    // The west strip (cells with a NaN corner in every triangle) and the hole's 8x8 inner cells
    // are gone; cells on the hole's rim keep the half whose corners are all valid.
    EXPECT_LE(area, 64.0 * 64.0 - 3.0 * 64.0 - 8.0 * 8.0);
    EXPECT_GE(area, 64.0 * 64.0 - 3.0 * 64.0 - 10.0 * 10.0);
}

TEST(RtinMesher, NormalsFromPostsAndPositionsRelativeToOrigin) {
    // z = 0.5 * east - 0.25 * north (metres); rows go south, so north = -(row) * pixelY.
    const MeshParams p = params(0.0, 0.0);
    const io::RasterTile tile = makeTile(17, [&](int x, int y) {
        const double east = (x + 0.5) * p.pixelX, north = -(y + 0.5) * p.pixelY;
        return float(100 + 0.5 * east - 0.25 * north);
    });
    RtinMesher mesher;
    auto mesh = mesher.build(tile, p);
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(mesh->origin, glm::dvec3(1000.0, 5000.0, 0.0));
    EXPECT_EQ(mesh->skirtTriangleCount(), 0u);
    const glm::dvec3 expected = glm::normalize(glm::dvec3(-0.5, 0.25, 1.0));
    for (std::size_t v = 0; v < mesh->vertexCount(); ++v) {
        const float* f = &mesh->vertices[v * 6];
        EXPECT_NEAR(f[3], expected.x, 1e-5);
        EXPECT_NEAR(f[4], expected.y, 1e-5);
        EXPECT_NEAR(f[5], expected.z, 1e-5);
        EXPECT_NEAR(f[2], 100 + 0.5 * f[0] - 0.25 * f[1], 1e-3);
    }
    EXPECT_NEAR(mesh->minZ,
                std::min({tile.at(0, 0), tile.at(16, 0), tile.at(0, 16), tile.at(16, 16)}), 1e-4);
}

struct BadTile {
    const char* name;
    int postsX, postsY;
    std::size_t values;
    double pixel;
    const char* code;
    const char* message;
};

class RtinMesherBadInput : public ::testing::TestWithParam<BadTile> {};

TEST_P(RtinMesherBadInput, ReportsCodeAndTile) {
    const BadTile& b = GetParam();
    io::RasterTile t;
    t.id = TileId{4, 7, 9};
    t.postsX = b.postsX;
    t.postsY = b.postsY;
    t.values.assign(b.values, 1.0f);
    MeshParams p = params(0.5);
    p.pixelX = b.pixel;
    RtinMesher mesher;
    auto r = mesher.build(t, p);
    ASSERT_FALSE(r.ok());
    const Diagnostic* d = r.diagnostics.firstError();
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->code, b.code);
    EXPECT_EQ(d->where, "tile 4/7/9");
    EXPECT_NE(d->message.find(b.message), std::string::npos) << d->message;
}

INSTANTIATE_TEST_SUITE_P(
    Table, RtinMesherBadInput,
    ::testing::Values(
        BadTile{"NotPowerOfTwo", 100, 100, 10000, 1.0, "TERRAIN_TILE_SHAPE", "got 100x100"},
        BadTile{"NotSquare", 257, 129, 257 * 129, 1.0, "TERRAIN_TILE_SHAPE", "257x129"},
        BadTile{"ShortValues", 257, 257, 1000, 1.0, "TERRAIN_TILE_SHAPE", "with 1000 values"},
        BadTile{"Empty", 0, 0, 0, 1.0, "TERRAIN_TILE_SHAPE", "got 0x0"},
        BadTile{"ZeroSpacing", 17, 17, 289, 0.0, "TERRAIN_MESH_PARAMS", "spacing"}),
    [](const auto& p) { return std::string(p.param.name); });

TEST(RtinMesher, BuildTileMeshUsesLevelToleranceAndTileOrigin) {
    io::TileGrid grid;
    grid.minX = 500000;
    grid.maxY = 5200000;
    grid.setPyramid(3, 256, 256, 10.0);  // 40 m pixels at level 0
    io::RasterTile tile = makeTile(257, bowl);
    tile.id = TileId{1, 1, 0};
    tile.stats.geometricError = 3.0f;
    TerrainOptions opt;
    RtinMesher mesher;
    auto mesh = buildTileMesh(tile, grid, opt, mesher);
    ASSERT_TRUE(mesh.ok());
    EXPECT_DOUBLE_EQ(mesh->tolerance, 0.5 * 3.0);  // half the tile's stored error
    EXPECT_DOUBLE_EQ(mesh->skirtDepth, opt.skirtDepth(grid, 1, 3.0));
    EXPECT_EQ(mesh->origin, glm::dvec3(500000 + 256 * 20.0, 5200000, 0.0));

    auto full = buildTileMesh(tile, grid, TerrainOptions::fullResolutionReference(), mesher);
    ASSERT_TRUE(full.ok());
    EXPECT_EQ(full->tolerance, 0.0);
    EXPECT_EQ(full->surfaceTriangleCount(), 2u * 256u * 256u);

    tile.id = TileId{5, 0, 0};
    auto bad = buildTileMesh(tile, grid, opt, mesher);
    ASSERT_FALSE(bad.ok());
    EXPECT_TRUE(bad.diagnostics.has("TERRAIN_TILE_LEVEL"));
}

// The seed paper's Puget Sound heightmap (1025^2 UInt16, 0.1 m per unit, 160 m spacing): the
// bound holds on real data, and smoother lowland costs far fewer triangles than the mountain.
TEST(RtinMesher, RealPugetSoundWindows) {
    // KIOSK_SHARED_DATA, else ../shared/data relative to the repo root (the tests' cwd).
    const char* env = std::getenv("KIOSK_SHARED_DATA");
    const std::string path =
        std::string(env ? env : "../shared/data") + "/puget_sound_heightmap/ps_height_1k.png";
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << path << " not found (set KIOSK_SHARED_DATA to the shared data folder)";
    auto in = OIIO::ImageInput::open(path);
    if (!in) GTEST_SKIP() << "cannot open " << path << ": " << OIIO::geterror();
    const OIIO::ImageSpec spec = in->spec();
    ASSERT_EQ(spec.width, 1025);
    std::vector<std::uint16_t> raw(std::size_t(spec.width) * std::size_t(spec.height));
    ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, raw.data()));
    // Rainier: the highest sample; water: the 257^2 window (on a 64-sample raster) of least
    // relief, in the sound at the upper left.
    const auto peak = std::size_t(std::max_element(raw.begin(), raw.end()) - raw.begin());
    int flatX = 0, flatY = 0, flatRange = 1 << 20;
    for (int wy = 0; wy + 257 <= spec.height; wy += 64)
        for (int wx = 0; wx + 257 <= spec.width; wx += 64) {
            int lo = 1 << 20, hi = 0;
            for (int y = wy; y < wy + 257; ++y)
                for (int x = wx; x < wx + 257; ++x) {
                    const int v = raw[std::size_t(y) * std::size_t(spec.width) + std::size_t(x)];
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                }
            if (hi - lo < flatRange) {
                flatRange = hi - lo;
                flatX = wx + 128;
                flatY = wy + 128;
            }
        }
    auto window = [&](int cx, int cy) {
        const int x0 = std::clamp(cx - 128, 0, spec.width - 257);
        const int y0 = std::clamp(cy - 128, 0, spec.height - 257);
        return makeTile(257, [&](int x, int y) {
            return float(0.1 *
                         raw[std::size_t(y0 + y) * std::size_t(spec.width) + std::size_t(x0 + x)]);
        });
    };
    const io::RasterTile mountain = window(int(peak % 1025u), int(peak / 1025u));
    const io::RasterTile water = window(flatX, flatY);
    RtinMesher mesher;
    MeshParams p = params(0.0, 10.0);
    p.pixelX = p.pixelY = 160.0;
    std::size_t prevMountain = SIZE_MAX, prevWater = SIZE_MAX;
    for (double tol : {1.0, 5.0, 20.0}) {
        p.tolerance = tol;
        auto m = mesher.build(mountain, p);
        auto w = mesher.build(water, p);
        ASSERT_TRUE(m.ok() && w.ok());
        EXPECT_LE(bruteForceError(*m, mountain, p).first, tol + 1e-3);
        EXPECT_LE(bruteForceError(*w, water, p).first, tol + 1e-3);
        std::cout << "ps_height_1k 257^2 tolerance " << tol << " m: Rainier "
                  << m->surfaceTriangleCount() << " triangles, lowland "
                  << w->surfaceTriangleCount() << " (full " << 2 * 256 * 256 << ", lowland relief "
                  << flatRange / 10.0 << " m)\n";
        EXPECT_LT(w->surfaceTriangleCount(), m->surfaceTriangleCount());
        EXPECT_LT(m->surfaceTriangleCount(), prevMountain);
        EXPECT_LT(w->surfaceTriangleCount(), prevWater);
        prevMountain = m->surfaceTriangleCount();
        prevWater = w->surfaceTriangleCount();
    }
    EXPECT_LT(prevWater * 4, std::size_t(2 * 256 * 256));  // 20 m: under a quarter of full
}

}  // namespace
}  // namespace kiosk::terrain
