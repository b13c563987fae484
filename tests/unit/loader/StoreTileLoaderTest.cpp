#include "runtime/loader/StoreTileLoader.h"
#include "runtime/terrain/TileSelector.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <set>
#include <thread>

namespace kiosk::loader {
namespace {

using terrain::TileKey;
using terrain::TilePayload;

std::string where(const std::string& layer, const TileId& id) {
    return layer + " tile " + std::to_string(id.level) + "/" + std::to_string(id.column) + "/" +
           std::to_string(id.row);
}

/** @brief In-memory store with the StoreReader interface: 3 levels over 4096 m. */
class FakeStore final : public io::StoreReader {
public:
    std::set<TileId> missing, corrupt, misshapen;

    FakeStore() {
        mInfo.path = "fake.gpkg";
        io::TileGrid& g = mInfo.grid;
        g.minX = 500000;
        g.minY = 5000000;
        g.maxX = g.minX + 4096;
        g.maxY = g.minY + 4096;
        g.setPyramid(3, 256, 256, 4.0);  // 16 m pixels at level 0
        mInfo.layers.push_back(io::LayerInfo{"elevation",
                                             io::LayerKind::Elevation,
                                             "m",
                                             0,
                                             100,
                                             {},
                                             3,
                                             21,
                                             g.minX,
                                             g.minY,
                                             g.maxX,
                                             g.maxY});
        mInfo.layers.push_back(io::LayerInfo{"imagery",
                                             io::LayerKind::Imagery,
                                             "",
                                             0,
                                             255,
                                             {},
                                             3,
                                             21,
                                             g.minX,
                                             g.minY,
                                             g.maxX,
                                             g.maxY});
    }
    static double height(double x, double y) {
        return 50 + 20 * std::sin(x / 300.0) * std::cos(y / 250.0);
    }

    const io::StoreInfo& info() const noexcept override { return mInfo; }

    Result<io::RasterTile> readElevation(const std::string& layer, const TileId& id) override {
        if (auto bad = failure(layer, id)) return *bad;
        io::RasterTile t;
        t.id = id;
        t.postsX = t.postsY = misshapen.count(id) ? 100 : 257;
        double x0, y0, x1, y1;
        mInfo.grid.tileBounds(id, x0, y0, x1, y1);
        const double px = mInfo.grid.levels[std::size_t(id.level)].pixelXSize;
        t.values.resize(std::size_t(t.postsX) * std::size_t(t.postsY));
        float lo = 1e9f, hi = -1e9f;
        for (int j = 0; j < t.postsY; ++j)
            for (int i = 0; i < t.postsX; ++i) {
                const float h = float(height(x0 + (i + 0.5) * px, y1 - (j + 0.5) * px));
                t.values[std::size_t(j * t.postsX + i)] = h;
                lo = std::min(lo, h);
                hi = std::max(hi, h);
            }
        t.stats = io::TileStats{lo, hi, float(id.level == 2 ? 0.0 : 4.0 / (1 << id.level))};
        return t;
    }
    Result<io::ImageTile> readImagery(const std::string& layer, const TileId& id) override {
        if (auto bad = failure(layer, id)) return Result<io::ImageTile>(bad->diagnostics);
        io::ImageTile img;
        img.id = id;
        img.width = img.height = 256;
        img.rgba.assign(256 * 256 * 4, std::uint8_t(id.level * 50));
        return img;
    }
    Result<io::RasterTile> readSequenceFrame(const std::string& seq, int frame,
                                             const TileId& id) override {
        if (auto bad = failure(seq, id)) return *bad;
        io::RasterTile t;
        t.id = id;
        t.postsX = t.postsY = 257;
        t.values.assign(257 * 257, float(frame));
        return t;
    }
    std::optional<io::TileStats> tileStats(const std::string&, const TileId&) override {
        return std::nullopt;
    }

private:
    std::optional<Result<io::RasterTile>> failure(const std::string& layer, const TileId& id) {
        Diagnostics d;
        if (missing.count(id))
            d.error("STORE_TILE_MISSING", mInfo.path, where(layer, id), "no such tile");
        else if (corrupt.count(id))
            d.error("STORE_TILE_CORRUPT", mInfo.path, where(layer, id), "bad PNG");
        else
            return std::nullopt;
        return Result<io::RasterTile>(std::move(d));
    }
    io::StoreInfo mInfo;
};

std::vector<LayerBinding> bindings() {
    return {{"elevation", io::LayerKind::Elevation},
            {"imagery", io::LayerKind::Imagery},
            {"flood", io::LayerKind::Sequence}};
}

StoreTileLoader makeLoader(const FakeStore& proto, terrain::TerrainOptions opt = {}) {
    return StoreTileLoader(
        [proto]() -> Result<std::unique_ptr<io::StoreReader>> {
            return std::unique_ptr<io::StoreReader>(std::make_unique<FakeStore>(proto));
        },
        bindings(), opt);
}

LoadRequest req(std::uint16_t layer, TileId id, int frame = 0) {
    return LoadRequest{TileKey{layer, frame, id}, 1.0, 1, false};
}

TEST(StoreTileLoader, ElevationBecomesMeshWithLevelTolerance) {
    FakeStore store;
    terrain::TerrainOptions opt;
    StoreTileLoader loader = makeLoader(store, opt);
    loader.threadStarted();
    const TileId id{1, 1, 0};
    const TilePayload p = loader.load(req(0, id));
    ASSERT_EQ(p.status, TilePayload::Status::Ready) << p.diagnostics.format();
    ASSERT_TRUE(p.mesh.has_value());
    ASSERT_TRUE(p.stats.has_value());
    EXPECT_EQ(p.mesh->id, id);
    EXPECT_EQ(p.mesh->origin, glm::dvec3(500000 + 2048, 5000000 + 4096, 0));
    EXPECT_DOUBLE_EQ(p.mesh->tolerance, opt.tinTolerance(p.stats->geometricError));
    EXPECT_DOUBLE_EQ(p.mesh->tolerance, 0.5 * 2.0);  // half of level 1's stored 2 m
    EXPECT_GT(p.mesh->skirtTriangleCount(), 0u);
    EXPECT_LT(p.mesh->surfaceTriangleCount(), 2u * 256u * 256u / 4u);  // smooth data: few triangles
    // Vertices are a subset of the posts, and the TIN stays within tolerance of the lowest one.
    EXPECT_GE(p.mesh->minZ, p.stats->minValue - 1e-3);
    EXPECT_LE(p.mesh->minZ, p.stats->minValue + p.mesh->tolerance + 1e-3);
    EXPECT_GT(p.byteSize(), p.mesh->byteSize());
    loader.threadStopping();
}

// The elevation key's frame is the tolerance tier: tier k doubles the tolerance k times and
// deepens the skirts to match; coarser tiers never have more triangles.
TEST(StoreTileLoader, ElevationFrameSelectsToleranceTier) {
    FakeStore store;
    terrain::TerrainOptions opt;
    StoreTileLoader loader = makeLoader(store, opt);
    loader.threadStarted();
    const TileId id{1, 1, 0};
    std::size_t previous = SIZE_MAX;
    for (int tier : {0, 1, 3}) {
        const TilePayload p = loader.load(req(0, id, tier));
        ASSERT_EQ(p.status, TilePayload::Status::Ready) << p.diagnostics.format();
        ASSERT_TRUE(p.mesh.has_value());
        EXPECT_DOUBLE_EQ(p.mesh->tolerance, 0.5 * 2.0 * double(1 << tier)) << "tier " << tier;
        EXPECT_DOUBLE_EQ(p.mesh->skirtDepth,
                         opt.skirtDepth(store.info().grid, 1, p.stats->geometricError, tier));
        EXPECT_LE(p.mesh->surfaceTriangleCount(), previous) << "tier " << tier;
        previous = p.mesh->surfaceTriangleCount();
    }
    loader.threadStopping();
}

TEST(StoreTileLoader, ImageryAndSequenceFrames) {
    FakeStore store;
    StoreTileLoader loader = makeLoader(store);
    loader.threadStarted();
    const TilePayload img = loader.load(req(1, TileId{2, 3, 1}));
    ASSERT_TRUE(img.image.has_value());
    EXPECT_EQ(img.image->rgba[0], 100);
    const TilePayload seq = loader.load(req(2, TileId{0, 0, 0}, 7));
    ASSERT_TRUE(seq.raster.has_value());
    EXPECT_EQ(seq.raster->values[5], 7.0f);
    EXPECT_FALSE(seq.mesh.has_value());
}

struct BadCase {
    const char* name;
    std::uint16_t layer;
    TileId id;
    TilePayload::Status status;
    const char* code;
    const char* where;
};

class StoreTileLoaderBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(StoreTileLoaderBad, ReportsCodeAndTile) {
    const BadCase& c = GetParam();
    FakeStore store;
    store.missing.insert(TileId{2, 0, 0});
    store.corrupt.insert(TileId{2, 1, 0});
    store.misshapen.insert(TileId{1, 0, 1});
    StoreTileLoader loader = makeLoader(store);
    loader.threadStarted();
    const TilePayload p = loader.load(req(c.layer, c.id));
    EXPECT_EQ(p.status, c.status);
    const Diagnostic* d = p.diagnostics.firstError();
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->code, c.code);
    EXPECT_EQ(d->where, c.where);
    EXPECT_FALSE(p.mesh.has_value());
    EXPECT_FALSE(p.image.has_value());
}

INSTANTIATE_TEST_SUITE_P(
    Table, StoreTileLoaderBad,
    ::testing::Values(BadCase{"Missing", 0, TileId{2, 0, 0}, TilePayload::Status::Absent,
                              "STORE_TILE_MISSING", "elevation tile 2/0/0"},
                      BadCase{"MissingImagery", 1, TileId{2, 0, 0}, TilePayload::Status::Absent,
                              "STORE_TILE_MISSING", "imagery tile 2/0/0"},
                      BadCase{"Corrupt", 0, TileId{2, 1, 0}, TilePayload::Status::Failed,
                              "STORE_TILE_CORRUPT", "elevation tile 2/1/0"},
                      BadCase{"Misshapen", 0, TileId{1, 0, 1}, TilePayload::Status::Failed,
                              "TERRAIN_TILE_SHAPE", "elevation tile 1/0/1"},
                      BadCase{"UnknownLayer", 9, TileId{0, 0, 0}, TilePayload::Status::Failed,
                              "LOADER_UNKNOWN_LAYER", "layer index 9"}),
    [](const auto& p) { return std::string(p.param.name); });

TEST(StoreTileLoader, UnopenableStoreFailsEveryRequest) {
    StoreTileLoader loader(
        []() -> Result<std::unique_ptr<io::StoreReader>> {
            Diagnostics d;
            d.error("STORE_OPEN", "/nope.gpkg", "", "unable to open database file");
            return Result<std::unique_ptr<io::StoreReader>>(std::move(d));
        },
        bindings(), {});
    loader.threadStarted();
    const TilePayload p = loader.load(req(0, TileId{0, 0, 0}));
    EXPECT_EQ(p.status, TilePayload::Status::Failed);
    ASSERT_NE(p.diagnostics.firstError(), nullptr);
    EXPECT_EQ(p.diagnostics.firstError()->code, "STORE_OPEN");
    EXPECT_EQ(p.diagnostics.firstError()->file, "/nope.gpkg");
}

// The whole CPU pipeline as the renderer will drive it: select -> request -> load thread ->
// drain -> cache, until every visible tile is drawn from its own payload, within the budget.
TEST(TerrainPipeline, ConvergesToResidentTilesWithinBudget) {
    FakeStore store;
    store.missing.insert(TileId{2, 3, 3});  // a hole in the data: must not be re-requested forever
    terrain::TerrainOptions opt;
    TileLoader loader(LoaderOptions{4, 256},
                      std::make_unique<StoreTileLoader>(makeLoader(store, opt)));

    terrain::TileSelector selector;
    terrain::SelectorSetup setup;
    setup.grid = store.info().grid;
    setup.geometryLayer = 0;
    setup.geometryMaxLevel = 2;
    setup.textures = {terrain::TextureLayerSpec{1, 0, 2}};
    setup.options = opt;
    selector.configure(setup);

    const terrain::CacheBudget budget{6u << 20, 1u << 20};
    terrain::TerrainTileCache cache(budget, 256);
    terrain::TileStatsTable stats;
    terrain::CacheResidency residency(cache, false);

    math::Viewpoint vp;
    vp.target = glm::dvec3(500000 + 2048, 5000000 + 2048, 50);
    vp.pitchDeg = -60;
    vp.range = 2500;
    const math::Camera cam = math::Camera::fromViewpoint(vp, 640, 360);

    bool converged = false;
    LoadResult r;
    for (std::uint64_t frame = 1; frame < 3000 && !converged; ++frame) {
        cache.beginFrame(frame);
        while (loader.tryPop(r)) {
            const bool elevation = r.request.key.layer == 0;
            if (elevation && r.payload.stats) stats.set(r.request.key.id, *r.payload.stats);
            if (elevation && r.payload.status == TilePayload::Status::Absent)
                stats.markAbsent(r.request.key.id);
            const std::size_t bytes = r.payload.byteSize();
            cache.insert(r.request.key, std::move(r.payload), bytes);
        }
        const terrain::SelectionResult& sel = selector.select(cam, stats, residency);
        std::size_t requested = 0;
        for (const auto& q : sel.requests)
            if (!cache.find(q.key).valid()) {
                loader.request(q.key, q.priority);
                ++requested;
            }
        loader.submit();
        ASSERT_LE(cache.cpuBytes(), budget.cpuBytes);
        converged = !sel.tiles.empty() && sel.counters.tilesFromAncestor == 0 && requested == 0 &&
                    sel.counters.tilesMissing == 0;
        if (converged) {
            for (const auto& t : sel.tiles) {
                const TilePayload* p = cache.get(t.handle);
                ASSERT_NE(p, nullptr);
                ASSERT_TRUE(p->mesh.has_value());
                EXPECT_EQ(p->mesh->id, t.geometry.id);
                EXPECT_NE(t.id, (TileId{2, 3, 3}));
                EXPECT_EQ(t.textureCount, 1u);
                EXPECT_TRUE(cache.get(sel.textures[t.firstTexture].handle)->image.has_value());
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_TRUE(converged);
}

}  // namespace
}  // namespace kiosk::loader
