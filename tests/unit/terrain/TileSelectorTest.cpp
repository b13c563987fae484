#include "runtime/terrain/TileSelector.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <set>
#include <string>
#include <tuple>

// Counts heap allocations so the test can prove select() is allocation-free once warm.
// (GCC 12 flags malloc/free inside replaced operators as mismatched: a false positive.)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
namespace {
std::atomic<std::size_t> gAllocations{0};
}
void* operator new(std::size_t n) {
    ++gAllocations;
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}

namespace kiosk::terrain {
namespace {

constexpr double kExtent = 4096.0;  // metres; level 0 pixel = 16 m
constexpr int kGeomMax = 4;

io::TileGrid makeGrid(int levels) {
    io::TileGrid g;
    g.minX = 0;
    g.minY = 0;
    g.maxX = kExtent;
    g.maxY = kExtent;
    g.setPyramid(levels, 256, 256, 16.0 / double(1 << (levels - 1)));  // 16 m at level 0
    return g;
}

double errorAt(int level) {
    return level >= kGeomMax ? 0.0 : 16.0 / double(1 << level);
}

void fillStats(TileStatsTable& t, int maxLevel, float minZ = 0, float maxZ = 50) {
    for (int l = 0; l <= maxLevel; ++l)
        for (int r = 0; r < (1 << l); ++r)
            for (int c = 0; c < (1 << l); ++c)
                t.set(TileId{l, c, r}, io::TileStats{minZ, maxZ, float(errorAt(l))});
}

/** @brief Residency over a key set (or everything): handles are opaque non-zero ids. */
class FakeResidency final : public TileResidency {
public:
    bool all = true;
    std::set<std::uint64_t> resident;
    int maxResidentLevel = 99;  // with all: only levels <= this are resident

    static std::uint64_t id(const TileKey& k) {
        return k.id.packed() ^ (std::uint64_t(k.layer) << 56);
    }
    void add(const TileKey& k) { resident.insert(id(k)); }
    TileHandle drawable(const TileKey& key) override {
        const bool ok = all ? key.id.level <= maxResidentLevel : resident.count(id(key)) > 0;
        return ok ? TileHandle{std::uint32_t(key.id.packed() % 1000003u) + 1u} : TileHandle{};
    }
};

math::Camera camera(glm::dvec3 target, double heading, double pitch, double range) {
    math::Viewpoint vp;
    vp.target = target;
    vp.headingDeg = heading;
    vp.pitchDeg = pitch;
    vp.range = range;
    return math::Camera::fromViewpoint(vp, 1280, 720);
}

struct Fixture {
    TileSelector selector;
    TileStatsTable stats;
    FakeResidency residency;

    explicit Fixture(int gridLevels = kGeomMax + 1, std::vector<TextureLayerSpec> textures = {},
                     TerrainOptions opt = {}) {
        SelectorSetup s;
        s.grid = makeGrid(gridLevels);
        s.geometryLayer = 0;
        s.geometryMaxLevel = kGeomMax;
        s.textures = std::move(textures);
        s.options = opt;
        selector.configure(std::move(s));
        fillStats(stats, kGeomMax);
    }
    const SelectionResult& select(const math::Camera& c) {
        return selector.select(c, stats, residency);
    }
};

bool isAncestor(const TileId& a, const TileId& d) {
    if (a.level >= d.level) return false;
    const int shift = d.level - a.level;
    return (d.column >> shift) == a.column && (d.row >> shift) == a.row;
}

void tileBounds(const TileId& id, double& x0, double& y0, double& x1, double& y1) {
    makeGrid(id.level + 1).tileBounds(id, x0, y0, x1, y1);
}

// Drawn tiles never overlap, and every terrain point inside the frustum is in exactly one.
void expectExactTiling(const SelectionResult& r, const math::Camera& cam, double z = 25.0) {
    for (std::size_t i = 0; i < r.tiles.size(); ++i)
        for (std::size_t j = 0; j < r.tiles.size(); ++j) {
            if (i == j) continue;
            ASSERT_NE(r.tiles[i].id, r.tiles[j].id) << "tile drawn twice";
            ASSERT_FALSE(isAncestor(r.tiles[i].id, r.tiles[j].id)) << "overlapping tiles";
        }
    const glm::dmat4 vp = cam.projection() * cam.view();
    int inside = 0;
    for (int sy = 0; sy < 64; ++sy)
        for (int sx = 0; sx < 64; ++sx) {
            const glm::dvec3 p((sx + 0.5) * kExtent / 64, (sy + 0.5) * kExtent / 64, z);
            const glm::dvec4 clip = vp * glm::dvec4(p, 1.0);
            if (clip.w <= 0 || std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w ||
                std::abs(clip.z) > clip.w)
                continue;
            ++inside;
            int containing = 0;
            for (const DrawTile& t : r.tiles) {
                double x0, y0, x1, y1;
                tileBounds(t.id, x0, y0, x1, y1);
                if (p.x >= x0 && p.x < x1 && p.y >= y0 && p.y < y1) ++containing;
            }
            ASSERT_EQ(containing, 1) << "point " << p.x << "," << p.y;
        }
    EXPECT_GT(inside, 0);
}

int levelAt(const SelectionResult& r, double x, double y) {
    for (const DrawTile& t : r.tiles) {
        double x0, y0, x1, y1;
        tileBounds(t.id, x0, y0, x1, y1);
        if (x >= x0 && x < x1 && y >= y0 && y < y1) return t.id.level;
    }
    return -1;
}

// Tolerance tiers: far finest-level tiles get coarser meshes (key frame = tier), close ones
// tier 0; a finer resident tier stands in without breaking the bound, a coarser one is a
// fallback that is flagged and requested with the error it shows.
TEST(TileSelector, ToleranceTiersFollowDistanceAndFallBack) {
    TerrainOptions opt;
    Fixture f(kGeomMax + 1, {}, opt);
    const auto cam = camera({2000, 2000, 25}, 0, -30, 300);
    const SelectionResult& r = f.select(cam);
    int finest = 0, tiered = 0, closeTierZero = 0;
    for (const DrawTile& t : r.tiles) {
        if (t.id.level != kGeomMax) continue;
        ++finest;
        tiered += t.geometry.frame > 0 ? 1 : 0;
        const double t0 = opt.tinTolerance(0.0);  // 0.1 m
        if (t0 * cam.pixelsPerMetreAt(t.distance) * 2 > opt.tauGeom) {
            EXPECT_EQ(t.geometry.frame, 0) << "close tile";
            ++closeTierZero;
        }
        EXPECT_LE(opt.tinTolerance(0.0, t.geometry.frame) * cam.pixelsPerMetreAt(t.distance),
                  opt.tauGeom + 1e-9);
    }
    ASSERT_GT(finest, 4);
    EXPECT_GT(tiered, 0) << "far finest tiles keep the 0.1 m mesh";
    EXPECT_GT(closeTierZero, 0);

    // Without tiers every mesh is tier 0.
    TerrainOptions none = opt;
    none.toleranceTiers = 0;
    Fixture g(kGeomMax + 1, {}, none);
    for (const DrawTile& t : g.select(cam).tiles) EXPECT_EQ(t.geometry.frame, 0);

    // Residency by exact key (frame included) for the fallbacks.
    class TierResidency final : public TileResidency {
    public:
        std::set<std::tuple<int, int, int, int>> keys;
        TileHandle drawable(const TileKey& k) override {
            return keys.count({k.frame, k.id.level, k.id.column, k.id.row})
                       ? TileHandle{std::uint32_t(k.id.packed() % 1000003u) + 1u}
                       : TileHandle{};
        }
    } res;
    // Pick one tiered tile; make only tier 0 of it resident (plus everything coarser).
    const DrawTile* pick = nullptr;
    for (const DrawTile& t : r.tiles)
        if (t.id.level == kGeomMax && t.geometry.frame >= 2) pick = &t;
    ASSERT_NE(pick, nullptr);
    const TileId id = pick->id;
    const int want = pick->geometry.frame;
    for (int l = 0; l < kGeomMax; ++l)
        for (int row = 0; row < (1 << l); ++row)
            for (int col = 0; col < (1 << l); ++col)
                for (int tier = 0; tier <= opt.maxToleranceTier(); ++tier)
                    res.keys.insert({tier, l, col, row});
    auto findTile = [&](const SelectionResult& sel) -> const DrawTile* {
        for (const DrawTile& t : sel.tiles)
            if (t.id == id) return &t;
        return nullptr;
    };
    auto requestFor = [&](const SelectionResult& sel) -> const TileRequest* {
        for (const TileRequest& q : sel.requests)
            if (q.key == TileKey{0, want, id}) return &q;
        return nullptr;
    };
    res.keys.insert({0, id.level, id.column, id.row});
    const SelectionResult& finer = f.selector.select(cam, f.stats, res);
    const DrawTile* d = findTile(finer);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->geometry, (TileKey{0, 0, id}));
    EXPECT_FALSE(d->fromAncestor);
    ASSERT_NE(requestFor(finer), nullptr);
    EXPECT_EQ(requestFor(finer)->priority, 0.0);  // only saves triangles

    res.keys.erase({0, id.level, id.column, id.row});
    res.keys.insert({want + 1, id.level, id.column, id.row});
    const SelectionResult& coarser = f.selector.select(cam, f.stats, res);
    d = findTile(coarser);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->geometry, (TileKey{0, want + 1, id}));
    EXPECT_TRUE(d->fromAncestor);
    ASSERT_NE(requestFor(coarser), nullptr);
    EXPECT_GT(requestFor(coarser)->priority, opt.tauGeom);

    // Only an ancestor's tiered mesh: drawn clipped, never a hole.
    res.keys.erase({want + 1, id.level, id.column, id.row});
    const SelectionResult& up = f.selector.select(cam, f.stats, res);
    d = findTile(up);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->geometry.id, id.parent());
    EXPECT_TRUE(d->clipped);
    EXPECT_EQ(up.counters.tilesMissing, 0u);
}

TEST(TileSelector, RefinementDecreasesMonotonicallyWithDistance) {
    Fixture f;
    int previousLevel = 99;
    std::size_t previousMax = 99;
    for (double range : {200.0, 400.0, 800.0, 1600.0, 3200.0, 6400.0, 12800.0, 40000.0}) {
        const auto cam = camera({2000, 2000, 25}, 0, -90, range);
        const SelectionResult& r = f.select(cam);
        const int level = levelAt(r, 2000, 2000);
        ASSERT_GE(level, 0);
        EXPECT_LE(level, previousLevel) << "range " << range;
        std::size_t maxLevel = 0;
        for (const auto& t : r.tiles)
            maxLevel = std::max<std::size_t>(maxLevel, std::size_t(t.id.level));
        EXPECT_LE(maxLevel, previousMax);
        previousLevel = level;
        previousMax = maxLevel;
    }
    EXPECT_EQ(f.select(camera({2000, 2000, 25}, 0, -90, 200)).counters.tilesDrawn > 1, true);
    EXPECT_EQ(levelAt(f.select(camera({2000, 2000, 25}, 0, -90, 200)), 2000, 2000), kGeomMax);
    const SelectionResult& far = f.select(camera({2000, 2000, 25}, 0, -90, 400000));
    ASSERT_EQ(far.tiles.size(), 1u);
    EXPECT_EQ(far.tiles[0].id, (TileId{0, 0, 0}));
}

TEST(TileSelector, EveryDrawnTileMeetsTheBoundAndItsParentDoesNot) {
    TerrainOptions opt;
    for (double tau : {1.0, 4.0}) {
        opt.tauGeom = tau;
        Fixture f(kGeomMax + 1, {}, opt);
        const auto cam = camera({1500, 2500, 25}, 30, -25, 1500);
        const SelectionResult& r = f.select(cam);
        ASSERT_GT(r.tiles.size(), 4u);
        const TerrainOptions& o = f.selector.setup().options;
        for (const DrawTile& t : r.tiles) {
            // The drawn mesh is the coarsest tolerance tier that meets the bound.
            const int tier = t.geometry.frame;
            const double l = errorAt(t.id.level);
            const double e = l + o.tinTolerance(l, tier);
            if (t.id.level < kGeomMax || tier > 0) {
                EXPECT_LE(e * cam.pixelsPerMetreAt(t.distance), tau + 1e-9);
            }
            if (tier < o.maxToleranceTier()) {
                EXPECT_GT((l + o.tinTolerance(l, tier + 1)) * cam.pixelsPerMetreAt(t.distance), tau)
                    << "a coarser tier would do for " << t.id.level << "/" << t.id.column;
            }
            EXPECT_NEAR(t.geometricErrorPx, e * cam.pixelsPerMetreAt(t.distance), 1e-9);
            if (t.id.level == 0) continue;
            const TileId p = t.id.parent();
            const double pe = errorAt(p.level) + o.tinTolerance(errorAt(p.level));
            const math::Aabb box = f.selector.nodeBounds(p, 0 - pe, 50 + pe);
            EXPECT_GT(pe * cam.pixelsPerMetreAt(box.distanceTo(cam.eye)), tau)
                << "tile " << t.id.level << "/" << t.id.column << "/" << t.id.row
                << " needlessly refined";
        }
    }
}

TEST(TileSelector, DrawnTilesPartitionTheVisibleExtent) {
    Fixture f;
    for (const auto& cam :
         {camera({2048, 2048, 25}, 0, -90, 3000), camera({1000, 1200, 25}, 45, -30, 900),
          camera({3000, 500, 25}, 200, -15, 600), camera({2048, 2048, 25}, 10, -60, 150)}) {
        const SelectionResult& r = f.select(cam);
        expectExactTiling(r, cam);
        EXPECT_EQ(r.counters.tilesDrawn, r.tiles.size());
        EXPECT_EQ(r.counters.tilesFromAncestor, 0u);
        EXPECT_TRUE(r.requests.empty());
    }
}

TEST(TileSelector, FrustumCullsTilesBehindAndBesideTheCamera) {
    Fixture f;
    // Low camera at the west part looking east.
    const auto cam = camera({1200, 2048, 25}, 90, -20, 600);
    const SelectionResult& r = f.select(cam);
    EXPECT_GT(r.counters.culled, 0u);
    ASSERT_FALSE(r.tiles.empty());
    for (const DrawTile& t : r.tiles) {
        double x0, y0, x1, y1;
        tileBounds(t.id, x0, y0, x1, y1);
        EXPECT_GT(x1 + 16.0, cam.eye.x) << "tile entirely behind the camera was drawn";
    }
    EXPECT_GE(levelAt(r, 1200, 2048), 0) << "the target's tile must be drawn";
    // Same view turned around: the target's tile is now behind and must be gone.
    const auto back = camera({cam.eye.x - 600, 2048, 25}, 270, -20, 600);
    EXPECT_EQ(levelAt(f.select(back), 1400, 2048), -1);
}

TEST(TileSelector, TextureFinerThanGeometryDrawsClippedGeometry) {
    // Imagery two levels finer than the elevation pyramid, both allowed.
    TerrainOptions opt;
    opt.textureLevelsBeyondGeometry = 2;
    Fixture capped(kGeomMax + 3, {TextureLayerSpec{1, 0, kGeomMax + 2}});
    EXPECT_EQ(levelAt(capped.select(camera({2048, 2048, 25}, 0, -90, 120)), 2048, 2048),
              kGeomMax + 1)
        << "default allows one texture level beyond the elevation pyramid";
    Fixture f(kGeomMax + 3, {TextureLayerSpec{1, 0, kGeomMax + 2}}, opt);
    const auto cam = camera({2048, 2048, 25}, 0, -90, 120);
    const SelectionResult& r = f.select(cam);
    const int level = levelAt(r, 2048, 2048);
    EXPECT_EQ(level, kGeomMax + 2);
    bool sawFine = false;
    for (const DrawTile& t : r.tiles) {
        ASSERT_EQ(t.textureCount, 1u);
        const TextureAssignment& ta = r.textures[t.firstTexture];
        EXPECT_LE(ta.key.id.level, t.id.level);
        if (t.id.level > kGeomMax) {
            sawFine = true;
            EXPECT_EQ(t.geometry.id.level, kGeomMax);
            EXPECT_TRUE(t.clipped);
            EXPECT_FALSE(t.fromAncestor);  // the finest mesh there is, not a loading fallback
            EXPECT_TRUE(isAncestor(t.geometry.id, t.id));
        }
    }
    EXPECT_TRUE(sawFine);
    expectExactTiling(r, cam);
}

// Issue 12 (cracks): a node refined for texture only keeps sides on its geometry tile G's
// border opened so G's surface and skirts are kept there (clipping at the node's own half post
// cut G's surface short on its east/south border and dropped its skirts). Issue 16: its sides
// inside G are its own tile edges, so its texture covers everything it draws (on G's post grid,
// half a post off, each node showed a strip of its neighbour's ground in clamped texels).
TEST(TileSelector, TextureOnlyNodesCoverTheirShareOfTheGeometryMesh) {
    TerrainOptions opt;
    opt.textureLevelsBeyondGeometry = 2;
    Fixture f(kGeomMax + 3, {TextureLayerSpec{1, 0, kGeomMax + 2}}, opt);
    const auto cam = camera({2048, 2048, 25}, 0, -90, 120);
    const SelectionResult& r = f.select(cam);
    int inner = 0, border = 0;
    for (const DrawTile& t : r.tiles) {
        if (!t.clipped) continue;
        ASSERT_FALSE(t.fromAncestor);
        EXPECT_EQ(t.domainLevel, t.id.level);  // clip edges on the node's own tile edges
        const double gp = 16.0 / double(1 << t.geometry.id.level);  // G's post spacing
        double x0, y0, x1, y1, gx0, gy0, gx1, gy1;
        tileBounds(t.id, x0, y0, x1, y1);
        tileBounds(t.geometry.id, gx0, gy0, gx1, gy1);
        // West/north: G's skirt bottom lies on G's bounds; east/south: a post of G outside.
        EXPECT_EQ(t.clipMin.x, x0 == gx0 ? gx0 - gp : x0);
        EXPECT_EQ(t.clipMax.y, y1 == gy1 ? gy1 + gp : y1);
        EXPECT_EQ(t.clipMax.x, x1 == gx1 ? gx1 + 2.0 * gp : x1);
        EXPECT_EQ(t.clipMin.y, y0 == gy0 ? gy0 - 2.0 * gp : y0);
        // G's mesh surface spans [gx0 + gp/2, gx1 + gp/2]: every node on G's east border
        // reaches past it (the old clip stopped a quarter post of the node's level past x1).
        if (x1 == gx1) {
            EXPECT_GT(t.clipMax.x, gx1 + gp);
        }
        const int onBorder = (x0 == gx0) + (x1 == gx1) + (y0 == gy0) + (y1 == gy1);
        border += onBorder;
        inner += 4 - onBorder;
    }
    EXPECT_GT(border, 0) << "sides on the geometry tile's border";
    EXPECT_GT(inner, 0) << "sides inside it";
}

TEST(TileSelector, TextureLevelIsChosenIndependentlyOfGeometry) {
    // Rough geometry refines deep; a lax tauTex lets the texture come from an ancestor level.
    TerrainOptions opt;
    opt.tauTex = 8.0;
    Fixture f(kGeomMax + 1, {TextureLayerSpec{1, 0, kGeomMax}, TextureLayerSpec{2, 0, 1}}, opt);
    const auto cam = camera({2048, 2048, 25}, 0, -60, 700);
    const SelectionResult& r = f.select(cam);
    int coarserTexture = 0;
    for (const DrawTile& t : r.tiles) {
        ASSERT_EQ(t.textureCount, 2u);
        const TextureAssignment& a = r.textures[t.firstTexture];
        const TextureAssignment& b = r.textures[t.firstTexture + 1];
        EXPECT_EQ(a.key.layer, 1);
        EXPECT_EQ(b.key.layer, 2);
        EXPECT_FALSE(a.fromAncestor);
        EXPECT_LE(b.key.id.level, 1);  // the layer has only two levels
        EXPECT_TRUE(a.key.id == t.id || isAncestor(a.key.id, t.id));
        // The chosen level's texel projects within tauTex, the next coarser one would not.
        const double ppm = cam.pixelsPerMetreAt(t.distance);
        const double texel = 16.0 / double(1 << a.key.id.level);
        EXPECT_LE(texel * ppm, 8.0 + 1e-9);
        if (a.key.id.level > 0) {
            EXPECT_GT(2 * texel * ppm, 8.0);
        }
        if (a.key.id.level < t.id.level) ++coarserTexture;
        double x0, y0, x1, y1;
        tileBounds(a.key.id, x0, y0, x1, y1);
        EXPECT_EQ(a.boundsMin, glm::dvec2(x0, y0));
        EXPECT_EQ(a.boundsMax, glm::dvec2(x1, y1));
    }
    EXPECT_GT(coarserTexture, 0) << "texture should come from an ancestor for some tiles";

    // Flat terrain (no geometric error): only the texture criterion refines.
    Fixture flat(kGeomMax + 1, {TextureLayerSpec{1, 0, kGeomMax}});
    flat.stats.clear();
    for (int l = 0; l <= kGeomMax; ++l)
        for (int rr = 0; rr < (1 << l); ++rr)
            for (int c = 0; c < (1 << l); ++c)
                flat.stats.set(TileId{l, c, rr}, io::TileStats{10, 10, 0});
    TerrainOptions exact;
    exact.tinToleranceFactor = 0.0;
    exact.tinToleranceMin = 0.0;
    exact.tauTex = 1e9;
    flat.selector.setOptions(exact);
    EXPECT_EQ(flat.select(cam).tiles.size(), 1u);
    exact.tauTex = 1.0;
    flat.selector.setOptions(exact);
    EXPECT_GT(flat.select(cam).tiles.size(), 1u);
}

TEST(TileSelector, FallsBackToNearestResidentAncestorAndRequests) {
    Fixture f(kGeomMax + 1, {TextureLayerSpec{1, 0, kGeomMax}});
    const auto cam = camera({2048, 2048, 25}, 0, -50, 500);
    f.residency.maxResidentLevel = 1;
    const SelectionResult& r = f.select(cam);
    ASSERT_FALSE(r.tiles.empty());
    std::set<std::uint64_t> requested;
    for (const TileRequest& q : r.requests) {
        EXPECT_TRUE(requested.insert(FakeResidency::id(q.key)).second) << "duplicate request";
        EXPECT_GT(q.priority, 0.0);
    }
    std::uint32_t fallbacks = 0;
    for (const DrawTile& t : r.tiles) {
        if (t.id.level <= 1) continue;
        ++fallbacks;
        EXPECT_TRUE(t.fromAncestor);
        EXPECT_TRUE(t.clipped);
        EXPECT_EQ(t.geometry.id.level, 1);
        EXPECT_TRUE(isAncestor(t.geometry.id, t.id));
        EXPECT_TRUE(requested.count(FakeResidency::id(TileKey{0, 0, t.id})));
        const TextureAssignment& ta = r.textures[t.firstTexture];
        if (ta.wanted.id.level > 1) {
            EXPECT_TRUE(ta.fromAncestor);
            EXPECT_EQ(ta.key.id.level, 1);
            EXPECT_TRUE(requested.count(FakeResidency::id(ta.wanted)));
        }
        // Clip rectangle = the node's share of its planned geometry tile's mesh domain: half a
        // post of that tile's level east/south of the node's bounds; not opened on the planned
        // tile's border, since the ancestor drawn instead has no skirts there.
        double x0, y0, x1, y1;
        tileBounds(t.id, x0, y0, x1, y1);
        EXPECT_GT(t.domainLevel, t.geometry.id.level);
        EXPECT_LE(t.domainLevel, t.id.level);
        const double half = 0.5 * 16.0 / double(1 << t.domainLevel);
        EXPECT_EQ(t.clipMin, glm::dvec2(x0 + half, y0 - half));
        EXPECT_EQ(t.clipMax, glm::dvec2(x1 + half, y1 - half));
    }
    EXPECT_GT(fallbacks, 0u);
    EXPECT_EQ(r.counters.geometryFromAncestor, fallbacks);
    EXPECT_EQ(r.counters.tilesFromAncestor, fallbacks);
    EXPECT_EQ(r.counters.requested, r.requests.size());
    expectExactTiling(r, cam);

    // Partial residency: some children arrived, their siblings still borrow the ancestor.
    f.residency.all = false;
    for (int l = 0; l <= 1; ++l)
        for (int rr = 0; rr < (1 << l); ++rr)
            for (int c = 0; c < (1 << l); ++c) f.residency.add(TileKey{0, 0, TileId{l, c, rr}});
    std::size_t own = 0;
    const std::vector<DrawTile> before = r.tiles;
    for (std::size_t i = 0; i < before.size(); i += 2) f.residency.add(TileKey{0, 0, before[i].id});
    const SelectionResult& r2 = f.select(cam);
    for (const DrawTile& t : r2.tiles) own += t.fromAncestor ? 0 : 1;
    EXPECT_GT(own, 0u);
    EXPECT_GT(r2.counters.geometryFromAncestor, 0u);
    expectExactTiling(r2, cam);
}

TEST(TileSelector, NothingResidentRequestsTheRootFirst) {
    Fixture f;
    f.residency.all = false;
    const SelectionResult& r = f.select(camera({2048, 2048, 25}, 0, -50, 500));
    EXPECT_TRUE(r.tiles.empty());
    EXPECT_GT(r.counters.tilesMissing, 0u);
    ASSERT_FALSE(r.requests.empty());
    const TileRequest* best = &r.requests[0];
    for (const auto& q : r.requests)
        if (q.priority > best->priority) best = &q;
    EXPECT_EQ(best->key.id, (TileId{0, 0, 0}));
}

TEST(TileSelector, UnknownAndAbsentStats) {
    Fixture f;
    f.stats.clear();
    f.stats.set(TileId{0, 0, 0}, io::TileStats{0, 50, 16});
    // Children unknown: they inherit the root's bounds and error, so refinement continues.
    const auto cam = camera({2048, 2048, 25}, 0, -90, 800);
    EXPECT_GT(f.select(cam).tiles.size(), 1u);
    // An absent quadrant is neither drawn nor requested.
    f.stats.markAbsent(TileId{1, 0, 0});
    const SelectionResult& r = f.select(cam);
    for (const DrawTile& t : r.tiles)
        EXPECT_FALSE(t.id == (TileId{1, 0, 0}) || isAncestor(TileId{1, 0, 0}, t.id));
    for (const TileRequest& q : r.requests) EXPECT_FALSE(isAncestor(TileId{1, 0, 0}, q.key.id));
}

TEST(TileSelector, FullResolutionSelectsFinestLevelEverywhere) {
    Fixture f(kGeomMax + 1, {}, TerrainOptions::fullResolutionReference());
    const auto cam = camera({2048, 2048, 25}, 0, -90, 30000);
    const SelectionResult& r = f.select(cam);
    EXPECT_EQ(r.tiles.size(), std::size_t(1) << (2 * kGeomMax));
    for (const DrawTile& t : r.tiles) {
        EXPECT_EQ(t.id.level, kGeomMax);
        EXPECT_EQ(t.geometricErrorPx, 0.0);  // error 0 at the finest level, tolerance 0
    }
    EXPECT_EQ(f.selector.setup().options.tinTolerance(12.0), 0.0);
}

TEST(TileSelector, SelectDoesNotAllocateOnceWarm) {
    Fixture f(kGeomMax + 1, {TextureLayerSpec{1, 0, kGeomMax}});
    f.residency.maxResidentLevel = 2;  // exercise fallbacks and requests too
    std::vector<math::Camera> path;
    for (int i = 0; i < 20; ++i)
        path.push_back(camera({1000.0 + 100 * i, 1500, 25}, 10.0 * i, -30, 400 + 50 * i));
    for (const auto& c : path) f.select(c);  // warm-up
    const std::size_t before = gAllocations.load();
    std::size_t drawn = 0;
    for (int pass = 0; pass < 3; ++pass)
        for (const auto& c : path) drawn += f.select(c).tiles.size();
    const std::size_t after = gAllocations.load();
    EXPECT_GT(drawn, 0u);
    EXPECT_EQ(after - before, 0u);
}

}  // namespace
}  // namespace kiosk::terrain

namespace kiosk::terrain {
namespace {

TEST(TileSelector, UnknownRootUsesTheSetupHeightRangeSoItIsNotCulled) {
    // High terrain seen horizontally: a root box at z = 0 would be below the frustum.
    SelectorSetup s;
    s.grid = makeGrid(kGeomMax + 1);
    s.geometryMaxLevel = kGeomMax;
    s.heightMin = 1900;
    s.heightMax = 2200;
    TileSelector selector;
    ASSERT_FALSE(selector.configure(s).hasErrors());
    TileStatsTable none;
    FakeResidency nothing;
    nothing.all = false;
    const auto cam = camera({300, 2048, 2050}, 90, 0, 1000);
    auto rootRequested = [](const SelectionResult& r) {
        bool found = false;
        for (const auto& q : r.requests) found |= q.key.id == TileId{0, 0, 0};
        return found;
    };
    EXPECT_TRUE(rootRequested(selector.select(cam, none, nothing)));
    // Control: assuming sea level instead, the root box falls below the frustum.
    s.heightMin = s.heightMax = 0;
    selector.configure(s);
    const SelectionResult& r = selector.select(cam, none, nothing);
    EXPECT_FALSE(rootRequested(r));
    EXPECT_EQ(r.counters.culled, 1u);
}

struct BadGrid {
    const char* name;
    int level;
    double pixel;
    int matrix;
    const char* where;
    const char* message;
};

class TileSelectorBadGrid : public ::testing::TestWithParam<BadGrid> {};

TEST_P(TileSelectorBadGrid, IsRejectedAndDrawsNothing) {
    const BadGrid& b = GetParam();
    SelectorSetup s;
    s.grid = makeGrid(4);
    s.grid.levels[std::size_t(b.level)].pixelXSize = b.pixel;
    s.grid.levels[std::size_t(b.level)].matrixWidth = b.matrix;
    s.geometryMaxLevel = 3;
    TileSelector selector;
    const Diagnostics d = selector.configure(s);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_EQ(d.firstError()->code, "TERRAIN_GRID_NOT_QUADTREE");
    EXPECT_EQ(d.firstError()->where, b.where);
    EXPECT_NE(d.firstError()->message.find(b.message), std::string::npos)
        << d.firstError()->message;
    TileStatsTable stats;
    FakeResidency all;
    const SelectionResult& r = selector.select(camera({2048, 2048, 25}, 0, -60, 900), stats, all);
    EXPECT_TRUE(r.tiles.empty());
    EXPECT_TRUE(r.requests.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Table, TileSelectorBadGrid,
    ::testing::Values(
        BadGrid{"NotHalved", 2, 3.0, 4, "tile matrix level 2", "not half of level 1"},
        BadGrid{"TooManyTiles", 1, 8.0, 5, "tile matrix level 1", "more than twice the tiles"},
        BadGrid{"ZeroPixel", 0, 0.0, 1, "tile matrix level 0", "non-positive pixel size"},
        BadGrid{"EmptyMatrix", 3, 2.0, 0, "tile matrix level 3", "empty matrix"}),
    [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace kiosk::terrain
