// `geokiosk import textures` (issue 20, docs/terrain.md §11): the store's imagery layers get ASTC
// 4x4 blocks with every mip level beside their PNG tiles; the loader hands them on undecoded when
// asked for the format, reads the PNG when the store has none or a row is damaged (one warning
// naming the tile); data layers are refused; the integrity checks know the table.
#include "runtime/app/TextureCommand.h"
#include "runtime/core/ExitCode.h"
#include "runtime/import/TextureCompression.h"
#include "runtime/import/Topographic.h"
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreIntegrity.h"
#include "runtime/loader/StoreTileLoader.h"
#include "tests/support/FloatTiff.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <cmath>
#include <vector>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import::test;

namespace {

// 600 x 600 posts of 30 m hills (three levels), hillshaded: an imagery layer of 21 tiles.
fs::path makeShadedStore(const fs::path& dir) {
    const fs::path tif = dir / "hills.tif";
    const std::string why =
        kiosk::test::writeFloatTiff(tif.string(), 600, 550000.0, 5200000.0, 30.0, [](int x, int y) {
            return float(900.0 + 600.0 * std::sin(x * 0.017) * std::cos(y * 0.012) +
                         25.0 * std::sin(x * 0.19 + y * 0.23));
        });
    EXPECT_EQ(why, "");
    const fs::path store = dir / "s.gpkg";
    Diagnostics d = import::importElevation(tif.string(), options(store));
    EXPECT_FALSE(d.hasErrors()) << d.format();
    import::TopographicOptions t;
    t.store = store;
    t.quiet = true;
    d = import::importTopographic(t);
    EXPECT_FALSE(d.hasErrors()) << d.format();
    return store;
}

std::int64_t count(const fs::path& store, const std::string& sql) {
    auto db = io::SqliteDb::open(store, io::SqliteDb::Mode::ReadOnly);
    EXPECT_TRUE(db.ok());
    return db->queryInt(sql).value_or(-1);
}

void run(const fs::path& store, const std::string& sql) {
    auto db = io::SqliteDb::open(store, io::SqliteDb::Mode::ReadWrite);
    ASSERT_TRUE(db.ok());
    const Diagnostics d = db->exec(sql);
    ASSERT_FALSE(d.hasErrors()) << d.format();
}

terrain::TilePayload loadImagery(const fs::path& store, const TileId& id,
                                 io::TextureFormat format) {
    loader::StoreTileLoader l(
        [store] { return io::StoreReader::open(store); },
        {{"elevation", io::LayerKind::Elevation}, {"hillshade", io::LayerKind::Imagery}},
        terrain::TerrainOptions{});
    l.setTextureFormat(format);
    l.threadStarted();
    loader::LoadRequest req;
    req.key.layer = 1;
    req.key.id = id;
    terrain::TilePayload p = l.load(req);
    l.threadStopping();
    return p;
}

import::TextureImportOptions fast(const fs::path& store){import::TextureImportOptions o;
o.store = store;
o.quality = import::AstcQuality::Fast;
o.quiet = true;
return o;
}  // namespace

}  // namespace

TEST(TextureImport, EveryImageryTileGetsBlocksTheLoaderHandsOn) {
    const fs::path dir = freshTestDir("geokiosk-texture-import");
    const fs::path store = makeShadedStore(dir);
    const std::int64_t tiles = count(store, "SELECT COUNT(*) FROM hillshade");
    ASSERT_GT(tiles, 4);
    auto r = import::importTextureBlocks(fast(store));
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    ASSERT_EQ(r->size(), 1u) << "the store's one imagery layer";
    const import::TextureLayerReport& rep = (*r)[0];
    EXPECT_EQ(rep.layer, "hillshade");
    EXPECT_EQ(std::int64_t(rep.tiles), tiles);
    // Hillshade is smooth: ASTC 4x4 keeps it far above 40 dB (docs/terrain.md §11).
    EXPECT_GT(rep.psnrMinDb, 40.0);
    EXPECT_GE(rep.psnrMedianDb, rep.psnrMinDb);
    // 8 bits a texel against 32: a quarter, every level included.
    EXPECT_NEAR(double(rep.blockBytes) / double(rep.rgbaBytes), 0.25, 0.01);
    RecordProperty("psnr_min_db", std::to_string(rep.psnrMinDb));
    RecordProperty("psnr_median_db", std::to_string(rep.psnrMedianDb));
    EXPECT_EQ(count(store,
                    "SELECT COUNT(*) FROM kiosk_tile_textures WHERE format = 'astc_4x4' "
                    "AND levels = 9 AND width = 256 AND height = 256"),
              tiles);
    EXPECT_EQ(count(store,
                    "SELECT COUNT(*) FROM gpkg_extensions WHERE table_name = "
                    "'kiosk_tile_textures' AND extension_name = 'kiosk_tile_textures'"),
              1);
    const Diagnostics deep = io::checkStoreIntegrity(store, io::IntegrityLevel::Deep);
    EXPECT_FALSE(deep.hasErrors()) << deep.format();

    // Asked for ASTC: the blocks as stored (no decode); not asked: the PNG as before.
    terrain::TilePayload c = loadImagery(store, TileId{1, 1, 0}, io::TextureFormat::Astc4x4);
    ASSERT_EQ(c.status, terrain::TilePayload::Status::Ready);
    ASSERT_TRUE(c.compressed);
    EXPECT_FALSE(c.image);
    EXPECT_TRUE(c.diagnostics.empty()) << c.diagnostics.format();
    EXPECT_EQ(c.compressed->levels, 9);
    EXPECT_EQ(c.compressed->blocks.size(), c.compressed->expectedBytes());
    EXPECT_EQ(c.compressed->levelOffset(1), std::size_t(64 * 64 * 16));
    terrain::TilePayload u = loadImagery(store, TileId{1, 1, 0}, io::TextureFormat::None);
    ASSERT_TRUE(u.image);
    EXPECT_FALSE(u.compressed);

    // Running it again replaces the layer's rows.
    ASSERT_TRUE(import::importTextureBlocks(fast(store)).ok());
    EXPECT_EQ(count(store, "SELECT COUNT(*) FROM kiosk_tile_textures"), tiles);
}

TEST(TextureImport, DamagedRowsFallBackToThePngNamingTheTile) {
    const fs::path dir = freshTestDir("geokiosk-texture-import");
    const fs::path store = makeShadedStore(dir);
    ASSERT_TRUE(import::importTextureBlocks(fast(store)).ok());
    // A short blob, and a row whose level count disagrees with its blob.
    run(store,
        "UPDATE kiosk_tile_textures SET blocks = substr(blocks, 1, 100) WHERE zoom_level = 1 AND "
        "tile_column = 1 AND tile_row = 0; UPDATE kiosk_tile_textures SET levels = 40 WHERE "
        "zoom_level = 1 AND tile_column = 0 AND tile_row = 1");
    for (const TileId id : {TileId{1, 1, 0}, TileId{1, 0, 1}}) {
        const std::string name =
            "hillshade/1/" + std::to_string(id.column) + "/" + std::to_string(id.row);
        SCOPED_TRACE(name);
        terrain::TilePayload p = loadImagery(store, id, io::TextureFormat::Astc4x4);
        ASSERT_EQ(p.status, terrain::TilePayload::Status::Ready);
        ASSERT_TRUE(p.image) << "the PNG is drawn instead";
        EXPECT_FALSE(p.compressed);
        ASSERT_EQ(p.diagnostics.size(), 1u) << p.diagnostics.format();
        const Diagnostic& w = p.diagnostics.items()[0];
        EXPECT_EQ(w.severity, Severity::Warning);
        EXPECT_EQ(w.code, "STORE_TEXTURE_CORRUPT");
        EXPECT_EQ(w.where, name);
        EXPECT_NE(w.format().find("PNG tile drawn instead"), std::string::npos) << w.format();
        EXPECT_EQ(w.format().find('\n'), std::string::npos) << "one line: " << w.format();
    }
    // Rows are fine for `validate`; --deep names both tiles.
    EXPECT_FALSE(io::checkStoreIntegrity(store, io::IntegrityLevel::Tables).hasErrors());
    const Diagnostics deep = io::checkStoreIntegrity(store, io::IntegrityLevel::Deep);
    ASSERT_EQ(deep.size(), 2u) << deep.format();
    EXPECT_EQ(deep.items()[0].code, "STORE_TEXTURE_CORRUPT");
    // Unregistered, and rows of a tile the layer does not have: integrity errors.
    run(store,
        "DELETE FROM gpkg_extensions WHERE table_name = 'kiosk_tile_textures'; UPDATE "
        "kiosk_tile_textures SET zoom_level = 7 WHERE zoom_level = 0");
    const std::string tables = io::checkStoreIntegrity(store, io::IntegrityLevel::Tables).format();
    EXPECT_NE(tables.find("not registered in gpkg_extensions"), std::string::npos) << tables;
    EXPECT_NE(tables.find("textures of tiles the table does not have"), std::string::npos)
        << tables;
}

TEST(TextureImport, StoresWithoutBlocksGiveThePng) {
    const fs::path dir = freshTestDir("geokiosk-texture-import");
    const fs::path store = makeShadedStore(dir);
    terrain::TilePayload p = loadImagery(store, TileId{0, 0, 0}, io::TextureFormat::Astc4x4);
    ASSERT_EQ(p.status, terrain::TilePayload::Status::Ready);
    EXPECT_TRUE(p.image);
    EXPECT_FALSE(p.compressed);
    EXPECT_TRUE(p.diagnostics.empty()) << p.diagnostics.format();
}

TEST(TextureImport, DataLayersAreNeverCompressed) {
    const fs::path dir = freshTestDir("geokiosk-texture-import");
    const fs::path store = makeShadedStore(dir);
    import::TextureImportOptions o = fast(store);
    o.layers = {"elevation"};
    auto r = import::importTextureBlocks(o);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.diagnostics.format().find("never lossy-compressed"), std::string::npos)
        << r.diagnostics.format();
    EXPECT_EQ(count(store,
                    "SELECT COUNT(*) FROM sqlite_master WHERE name = "
                    "'kiosk_tile_textures'"),
              0)
        << "the store is untouched";
    // Asked for blocks of an elevation layer, the reader has none to give.
    auto reader = openStore(store);
    ASSERT_TRUE(reader);
    io::CompressedImage img;
    auto none =
        reader->readTileTexture("elevation", TileId{0, 0, 0}, io::TextureFormat::Astc4x4, img);
    ASSERT_TRUE(none.ok());
    EXPECT_FALSE(*none);
}

TEST(TextureImport, CommandExitCodes) {
    const fs::path dir = freshTestDir("geokiosk-texture-import");
    const fs::path store = makeShadedStore(dir);
    const std::string s = store.string();
    EXPECT_EQ(app::runImportTextures({"--store", s, "--quality", "best"}), kExitUsage);
    EXPECT_EQ(app::runImportTextures({"--layers", "hillshade"}), kExitUsage);
    EXPECT_EQ(app::runImportTextures({"--store", s, "--layers", "hillshade,,x"}), kExitUsage);
    EXPECT_EQ(app::runImportTextures({"--store", s, "--threads", "0"}), kExitUsage);
    EXPECT_EQ(app::runImportTextures({"--store", (dir / "none.gpkg").string()}), kExitBadInput);
    EXPECT_EQ(app::runImportTextures({"--store", s, "--layers", "elevation", "--quiet"}),
              kExitBadInput);
    EXPECT_EQ(app::runImportTextures({"--store", s, "--layers", "nosuch", "--quiet"}),
              kExitBadInput);
    EXPECT_EQ(app::runImportTextures(
                  {"--store", s, "--layers", "hillshade", "--quality", "fast", "--quiet"}),
              kExitOk);
    EXPECT_GT(count(store, "SELECT COUNT(*) FROM kiosk_tile_textures"), 4);
}
