// `import elevation` stores every tile's simplified mesh (issue 20); the loader decodes it
// instead of meshing, falls back to the posts for a damaged blob (one warning naming the tile)
// and for stores imported before meshes were stored; the integrity checks know the table.
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreIntegrity.h"
#include "runtime/loader/StoreTileLoader.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <gdal.h>

#include <cmath>
#include <vector>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import::test;

namespace {

// 600 x 520 posts of 30 m mountain (UTM 10N): three levels, 14 tiles.
fs::path makeMountainDem(const fs::path& dir) {
    const int w = 600, h = 520;
    std::vector<float> v(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            v[std::size_t(y) * w + std::size_t(x)] =
                float(1200.0 + 900.0 * std::sin(x * 0.011) * std::cos(y * 0.013) +
                      40.0 * std::sin(x * 0.21 + y * 0.17));
    GDALAllRegister();
    const fs::path p = dir / "mountain.tif";
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), w, h, 1, GDT_Float32, nullptr);
    EXPECT_NE(ds, nullptr);
    double gt[6] = {550000.0, 30.0, 0.0, 5200000.0, 0.0, -30.0};
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, wktOf(32610).c_str());
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, w, h, v.data(), w, h,
                           GDT_Float32, 0, 0),
              CE_None);
    GDALClose(ds);
    return p;
}

struct Loaded {
    terrain::TilePayload stored, built;
};

// The same tile through the loader (stored mesh when there is one) and meshed from its posts.
Loaded load(const fs::path& store, const TileId& id, int tier) {
    loader::StoreTileLoader l([store] { return io::StoreReader::open(store); },
                              {{"elevation", io::LayerKind::Elevation}}, terrain::TerrainOptions{});
    l.threadStarted();
    loader::LoadRequest req;
    req.key.id = id;
    req.key.frame = tier;
    Loaded out;
    out.stored = l.load(req);
    l.threadStopping();
    auto reader = io::StoreReader::open(store);
    EXPECT_TRUE(reader.ok());
    auto posts = (*reader)->readElevation("elevation", id);
    EXPECT_TRUE(posts.ok());
    terrain::RtinMesher mesher;
    auto mesh = terrain::buildTileMesh(*posts, (*reader)->info().grid, terrain::TerrainOptions{},
                                       mesher, tier);
    EXPECT_TRUE(mesh.ok());
    out.built.mesh = std::move(*mesh.value);
    return out;
}

void expectSameMesh(const terrain::TileMesh& a, const terrain::TileMesh& b) {
    EXPECT_EQ(a.surfaceVertexCount, b.surfaceVertexCount);
    EXPECT_EQ(a.surfaceIndexCount, b.surfaceIndexCount);
    EXPECT_EQ(a.indices.size(), b.indices.size());
    EXPECT_EQ(a.vertexCount(), b.vertexCount());
    EXPECT_EQ(a.minZ, b.minZ);
    EXPECT_EQ(a.maxZ, b.maxZ);
    EXPECT_EQ(a.skirtDepth, b.skirtDepth);
    EXPECT_EQ(a.surfaceCellStart, b.surfaceCellStart);
    EXPECT_EQ(a.skirtCellStart, b.skirtCellStart);
}

std::int64_t queryInt(const fs::path& store, const std::string& sql) {
    auto db = io::SqliteDb::open(store, io::SqliteDb::Mode::ReadOnly);
    EXPECT_TRUE(db.ok());
    return db->queryInt(sql).value_or(-1);
}

void exec(const fs::path& store, const std::string& sql) {
    auto db = io::SqliteDb::open(store, io::SqliteDb::Mode::ReadWrite);
    ASSERT_TRUE(db.ok());
    const Diagnostics d = db->exec(sql);
    ASSERT_FALSE(d.hasErrors()) << d.format();
}

TEST(StoredMeshImport, EveryTileHasAMeshTheLoaderDecodes) {
    const fs::path dir = freshTestDir("geokiosk-stored-mesh");
    const fs::path store = dir / "s.gpkg";
    const Diagnostics d = import::importElevation(makeMountainDem(dir).string(), options(store));
    ASSERT_FALSE(d.hasErrors()) << d.format();
    // A tier-0 row per tile: interior tiles derive their coarser tiers from it (split tiers),
    // tiles at the data's edge (nodata) keep the coarser tiers with at most half of tier 0's
    // vertices whole (tier 10 always); registered as an extension.
    EXPECT_EQ(queryInt(store, "SELECT COUNT(*) FROM kiosk_tile_meshes WHERE tier = 0"), 14);
    const std::int64_t edge = queryInt(
        store, "SELECT COUNT(*) FROM kiosk_tile_meshes WHERE tier = 0 AND split_tiers = 0");
    EXPECT_GT(edge, 0);
    EXPECT_LT(edge, 14);
    EXPECT_EQ(queryInt(store, "SELECT COUNT(*) FROM kiosk_tile_meshes WHERE tier = 10"), edge);
    EXPECT_EQ(queryInt(store,
                       "SELECT COUNT(*) FROM kiosk_tile_meshes c JOIN kiosk_tile_meshes t0 USING "
                       "(table_name, zoom_level, tile_column, tile_row) WHERE c.tier > 0 AND "
                       "t0.tier = 0 AND (c.split_tiers = 1 OR t0.split_tiers = 1 OR "
                       "c.vertex_count * 2 > t0.vertex_count)"),
              0);
    EXPECT_EQ(queryInt(store,
                       "SELECT COUNT(*) FROM gpkg_extensions WHERE table_name = "
                       "'kiosk_tile_meshes' AND extension_name = 'kiosk_tile_meshes'"),
              1);
    const Diagnostics deep = io::checkStoreIntegrity(store, io::IntegrityLevel::Deep);
    EXPECT_FALSE(deep.hasErrors()) << deep.format();
    for (const TileId id : {TileId{0, 0, 0}, TileId{1, 1, 0}, TileId{2, 1, 1}, TileId{2, 2, 2}})
        for (int tier : {0, 1, 3, 10}) {
            SCOPED_TRACE("tile " + std::to_string(id.level) + "/" + std::to_string(id.column) +
                         "/" + std::to_string(id.row) + " tier " + std::to_string(tier));
            const Loaded l = load(store, id, tier);
            ASSERT_EQ(l.stored.status, terrain::TilePayload::Status::Ready);
            ASSERT_TRUE(l.stored.mesh && l.stored.stats);
            EXPECT_TRUE(l.stored.diagnostics.empty()) << l.stored.diagnostics.format();
            expectSameMesh(*l.stored.mesh, *l.built.mesh);
        }
}

TEST(StoredMeshImport, DamagedMeshIsMeshedFromPostsAndNamed) {
    const fs::path dir = freshTestDir("geokiosk-stored-mesh");
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(
        import::importElevation(makeMountainDem(dir).string(), options(store)).hasErrors());
    exec(store,
         "UPDATE kiosk_tile_meshes SET mesh = substr(mesh, 1, 60) WHERE table_name = "
         "'elevation' AND zoom_level = 2 AND tile_column = 1 AND tile_row = 1 AND tier = 0");
    const Loaded l = load(store, TileId{2, 1, 1}, 0);
    ASSERT_EQ(l.stored.status, terrain::TilePayload::Status::Ready);
    ASSERT_TRUE(l.stored.mesh);
    expectSameMesh(*l.stored.mesh, *l.built.mesh);
    ASSERT_EQ(l.stored.diagnostics.size(), 1u);
    const Diagnostic& w = l.stored.diagnostics.items()[0];
    EXPECT_EQ(w.severity, Severity::Warning);
    EXPECT_EQ(w.code, "STORE_MESH_CORRUPT");
    EXPECT_EQ(w.where, "elevation/2/1/1 tier 0") << w.format();
    // `validate` / `info --check` look at rows only; --deep decodes and names the tile.
    EXPECT_FALSE(io::checkStoreIntegrity(store, io::IntegrityLevel::Tables).hasErrors());
    const Diagnostics deep = io::checkStoreIntegrity(store, io::IntegrityLevel::Deep);
    ASSERT_EQ(deep.size(), 1u) << deep.format();
    EXPECT_EQ(deep.items()[0].code, "STORE_MESH_CORRUPT");
    EXPECT_EQ(deep.items()[0].where, "elevation/2/1/1 tier 0");
    // A mesh row without its tile, and an unregistered table, are integrity errors.
    exec(store,
         "DELETE FROM elevation WHERE zoom_level = 2 AND tile_column = 2 AND "
         "tile_row = 2; UPDATE kiosk_layers SET tile_count = tile_count - 1");
    exec(store, "DELETE FROM gpkg_extensions WHERE table_name = 'kiosk_tile_meshes'");
    const std::string tables = io::checkStoreIntegrity(store, io::IntegrityLevel::Tables).format();
    EXPECT_NE(tables.find("meshes of tiles the table does not have"), std::string::npos) << tables;
    EXPECT_NE(tables.find("not registered in gpkg_extensions"), std::string::npos) << tables;
}

// An edge tile's coarser tier is read from its own row, not meshed from the posts: a damaged
// tier-10 row is the warning that names it, and the posts give the same mesh.
TEST(StoredMeshImport, EdgeTilesReadTheirCoarserTiersFromTheirOwnRows) {
    const fs::path dir = freshTestDir("geokiosk-stored-mesh");
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(
        import::importElevation(makeMountainDem(dir).string(), options(store)).hasErrors());
    const std::string edge =
        " FROM kiosk_tile_meshes WHERE tier = 10 AND zoom_level = 2 ORDER BY "
        "tile_column DESC, tile_row DESC LIMIT 1";
    const TileId id{2, int(queryInt(store, "SELECT tile_column" + edge)),
                    int(queryInt(store, "SELECT tile_row" + edge))};
    ASSERT_GE(id.column, 0);
    const std::string name =
        "elevation/2/" + std::to_string(id.column) + "/" + std::to_string(id.row);
    const Loaded intact = load(store, id, 10);
    ASSERT_TRUE(intact.stored.mesh);
    EXPECT_TRUE(intact.stored.diagnostics.empty()) << intact.stored.diagnostics.format();
    expectSameMesh(*intact.stored.mesh, *intact.built.mesh);
    exec(store,
         "UPDATE kiosk_tile_meshes SET mesh = substr(mesh, 1, 60) WHERE zoom_level = 2 AND "
         "tile_column = " +
             std::to_string(id.column) + " AND tile_row = " + std::to_string(id.row) +
             " AND tier = 10");
    const Loaded l = load(store, id, 10);
    ASSERT_TRUE(l.stored.mesh);
    expectSameMesh(*l.stored.mesh, *l.built.mesh);
    ASSERT_EQ(l.stored.diagnostics.size(), 1u) << l.stored.diagnostics.format();
    EXPECT_EQ(l.stored.diagnostics.items()[0].code, "STORE_MESH_CORRUPT");
    EXPECT_EQ(l.stored.diagnostics.items()[0].where, name + " tier 10");
}

TEST(StoredMeshImport, StoresWithoutMeshesAreMeshedOnLoad) {
    const fs::path dir = freshTestDir("geokiosk-stored-mesh");
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(
        import::importElevation(makeMountainDem(dir).string(), options(store)).hasErrors());
    exec(store,
         "DROP TABLE kiosk_tile_meshes; DELETE FROM gpkg_extensions WHERE table_name = "
         "'kiosk_tile_meshes'");
    EXPECT_FALSE(io::checkStoreIntegrity(store, io::IntegrityLevel::Deep).hasErrors());
    const Loaded l = load(store, TileId{2, 1, 1}, 0);
    ASSERT_EQ(l.stored.status, terrain::TilePayload::Status::Ready);
    ASSERT_TRUE(l.stored.mesh);
    EXPECT_TRUE(l.stored.diagnostics.empty());
    expectSameMesh(*l.stored.mesh, *l.built.mesh);
}

}  // namespace
