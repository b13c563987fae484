#include "runtime/io/ImageCodec.h"
#include "runtime/io/ScalarTileCodec.h"
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreReader.h"
#include "runtime/io/StoreWriter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::io;

namespace {

constexpr int kT = 16;  // small tiles keep the test fast; the codec is size-agnostic

fs::path tempPath(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / "geokiosk-io-test";
    fs::create_directories(dir);
    fs::path p = dir / name;
    fs::remove(p);
    return p;
}

TileGrid smallGrid(int levels) {
    TileGrid g;
    g.srsId = 32610;
    g.crsName = "WGS 84 / UTM zone 10N";
    g.crsWkt = "PROJCS[\"WGS 84 / UTM zone 10N\"]";
    const double finest = 10.0;
    g.minX = 500000;
    g.maxY = 5200000;
    const double size = finest * kT * (1 << (levels - 1));
    g.maxX = g.minX + size;
    g.minY = g.maxY - size;
    g.setPyramid(levels, kT, kT, finest);
    return g;
}

float field(int gx, int gy) {
    return 100.0f + 0.37f * float(gx) - 0.21f * float(gy) + float((gx * gy) % 7);
}

std::vector<float> postsFor(int c, int r) {
    std::vector<float> p(std::size_t((kT + 1) * (kT + 1)));
    for (int y = 0; y <= kT; ++y)
        for (int x = 0; x <= kT; ++x)
            p[std::size_t(y * (kT + 1) + x)] = field(c * kT + x, r * kT + y);
    return p;
}

// A 2x2-tile finest level (level 1) plus a level-0 tile.
fs::path writeSmallStore(const std::string& name) {
    fs::path p = tempPath(name);
    auto w = StoreWriter::open(p, true);
    EXPECT_TRUE(w.ok()) << w.diagnostics.format();
    EXPECT_FALSE((*w)->defineGrid(smallGrid(2)).hasErrors());
    ScalarLayerSpec spec;
    spec.table = "elevation";
    spec.scale = 0.125;
    EXPECT_FALSE((*w)->createScalarLayer(spec).hasErrors());
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
            auto posts = postsFor(c, r);
            quantizePosts(posts, spec.scale);
            auto enc = encodeScalarTile(posts, kT, kT, spec.scale, 4);
            EXPECT_TRUE(enc.ok());
            enc->stats.geometricError = 0;
            EXPECT_FALSE((*w)->putScalarTile("elevation", TileId{1, c, r}, *enc).hasErrors());
        }
    auto posts = postsFor(0, 0);
    quantizePosts(posts, spec.scale);
    auto enc = encodeScalarTile(posts, kT, kT, spec.scale, 4);
    enc->stats.geometricError = 2.5f;
    EXPECT_FALSE((*w)->putScalarTile("elevation", TileId{0, 0, 0}, *enc).hasErrors());
    EXPECT_FALSE(
        (*w)->finishLayer("elevation", 90, 130, 500000, 5199680, 500320, 5200000).hasErrors());
    EXPECT_FALSE((*w)->createImageryLayer("imagery", "test").hasErrors());
    std::vector<std::uint8_t> rgba(std::size_t(kT * kT * 4));
    for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = std::uint8_t(i * 7);
    auto png = encodePng8(rgba.data(), kT, kT, 4, 6);
    EXPECT_TRUE(png.ok());
    EXPECT_FALSE((*w)->putImageTile("imagery", TileId{1, 0, 0}, *png).hasErrors());
    EXPECT_FALSE((*w)->commit().hasErrors());
    return p;
}

}  // namespace

TEST(ImageCodec, Png16RoundTripIsExact) {
    std::vector<std::uint16_t> v(64 * 48);
    std::mt19937 rng(7);
    for (auto& x : v) x = std::uint16_t(rng());
    auto png = encodePng16(v.data(), 64, 48, 6);
    ASSERT_TRUE(png.ok()) << png.diagnostics.format();
    EXPECT_EQ(sniffImageFormat(png->data(), png->size()), ImageFormat::Png);
    auto back = decodeGray16(png->data(), png->size(), "t");
    ASSERT_TRUE(back.ok()) << back.diagnostics.format();
    EXPECT_EQ(back->width, 64);
    EXPECT_EQ(back->height, 48);
    EXPECT_EQ(back->samples16, v);
}

TEST(ImageCodec, JpegDecodesToRgbaWithinLossyTolerance) {
    std::vector<std::uint8_t> rgb(32 * 32 * 3);
    for (int i = 0; i < 32 * 32; ++i) {
        rgb[std::size_t(i) * 3] = std::uint8_t(i % 32 * 8);
        rgb[std::size_t(i) * 3 + 1] = 128;
        rgb[std::size_t(i) * 3 + 2] = std::uint8_t(i / 32 * 8);
    }
    auto jpg = encodeJpeg(rgb.data(), 32, 32, 95);
    ASSERT_TRUE(jpg.ok());
    EXPECT_EQ(sniffImageFormat(jpg->data(), jpg->size()), ImageFormat::Jpeg);
    auto back = decodeRgba8(jpg->data(), jpg->size(), "t");
    ASSERT_TRUE(back.ok());
    int worst = 0;
    for (int i = 0; i < 32 * 32; ++i) {
        for (int c = 0; c < 3; ++c)
            worst =
                std::max(worst, std::abs(int(back->samples8[std::size_t(i) * 4 + std::size_t(c)]) -
                                         int(rgb[std::size_t(i) * 3 + std::size_t(c)])));
        EXPECT_EQ(back->samples8[std::size_t(i) * 4 + 3], 255);
    }
    EXPECT_LT(worst, 12);
}

TEST(ImageCodec, GarbageIsAnErrorNotACrash) {
    const std::uint8_t junk[] = {0x89, 'P', 'N', 'G', 1, 2, 3, 4, 5};
    auto r = decodeGray16(junk, sizeof junk, "layer/1/2/3");
    EXPECT_FALSE(r.ok());
    ASSERT_NE(r.diagnostics.firstError(), nullptr);
    EXPECT_EQ(r.diagnostics.firstError()->code, "IMAGE_DECODE");
    EXPECT_EQ(r.diagnostics.firstError()->where, "layer/1/2/3");
}

TEST(ScalarTileCodec, SharedPostsDecodeIdenticallyWhateverTheTileOffset) {
    // The same sample quantised in two tiles with different offsets must give the same float.
    const double scale = 0.125;
    std::vector<float> a(std::size_t((kT + 1) * (kT + 1)), 1000.3f), b = a;
    a[0] = 12.0f;    // tile a offset ~12
    b[0] = 3000.0f;  // tile b offset 1000
    a[std::size_t(kT)] = 1234.567f;
    b[std::size_t(kT)] = 1234.567f;
    quantizePosts(a, scale);
    quantizePosts(b, scale);
    auto ea = encodeScalarTile(a, kT, kT, scale, 4), eb = encodeScalarTile(b, kT, kT, scale, 4);
    ASSERT_TRUE(ea.ok() && eb.ok());
    EXPECT_NE(ea->offset, eb->offset);
    auto da = decodeScalarTile(ea->png.data(), ea->png.size(), nullptr, 0, ea->scale, ea->offset,
                               65535, kT, kT, "a");
    auto db = decodeScalarTile(eb->png.data(), eb->png.size(), nullptr, 0, eb->scale, eb->offset,
                               65535, kT, kT, "b");
    ASSERT_TRUE(da.ok() && db.ok());
    EXPECT_EQ(da->at(1, 1), db->at(1, 1));
    EXPECT_EQ(da->at(1, 1), float(std::nearbyint(1000.3 / scale) * scale));
}

TEST(StoreReader, RoundTripsPostsBordersStatsAndMetadata) {
    const fs::path p = writeSmallStore("roundtrip.gpkg");
    auto r = StoreReader::open(p);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const StoreInfo& info = (*r)->info();
    EXPECT_EQ(info.grid.srsId, 32610);
    EXPECT_EQ(info.grid.levels.size(), 2u);
    EXPECT_DOUBLE_EQ(info.grid.levels[0].pixelXSize, 20.0);
    ASSERT_NE(info.findLayer("elevation"), nullptr);
    EXPECT_EQ(info.findLayer("elevation")->tileCount, 5);
    EXPECT_EQ(info.findLayer("imagery")->kind, LayerKind::Imagery);
    EXPECT_GT(info.sizeBytes, 0);

    for (int r0 = 0; r0 < 2; ++r0)
        for (int c = 0; c < 2; ++c) {
            auto t = (*r)->readElevation("elevation", TileId{1, c, r0});
            ASSERT_TRUE(t.ok()) << t.diagnostics.format();
            ASSERT_EQ(t->postsX, kT + 1);
            for (int y = 0; y <= kT; ++y)
                for (int x = 0; x <= kT; ++x)
                    EXPECT_NEAR(t->at(x, y), field(c * kT + x, r0 * kT + y), 0.0625 + 1e-4)
                        << c << "," << r0 << " post " << x << "," << y;
        }
    // Border posts equal the neighbour's own samples bit for bit.
    auto w = (*r)->readElevation("elevation", TileId{1, 0, 0});
    auto e = (*r)->readElevation("elevation", TileId{1, 1, 0});
    auto s = (*r)->readElevation("elevation", TileId{1, 0, 1});
    for (int y = 0; y < kT; ++y) EXPECT_EQ(w->at(kT, y), e->at(0, y));
    for (int x = 0; x < kT; ++x) EXPECT_EQ(w->at(x, kT), s->at(x, 0));

    auto st = (*r)->tileStats("elevation", TileId{0, 0, 0});
    ASSERT_TRUE(st.has_value());
    EXPECT_FLOAT_EQ(st->geometricError, 2.5f);
    EXPECT_FALSE((*r)->tileStats("elevation", TileId{0, 0, 1}).has_value());

    auto img = (*r)->readImagery("imagery", TileId{1, 0, 0});
    ASSERT_TRUE(img.ok()) << img.diagnostics.format();
    EXPECT_EQ(img->width, kT);
    EXPECT_EQ(img->rgba[5], std::uint8_t(5 * 7));
}

TEST(StoreReader, HeaderIsGeoPackage13) {
    const fs::path p = writeSmallStore("header.gpkg");
    auto db = SqliteDb::open(p, SqliteDb::Mode::ReadOnly);
    ASSERT_TRUE(db.ok());
    EXPECT_EQ(db->queryInt("PRAGMA application_id"), 0x47504B47);
    EXPECT_EQ(db->queryInt("PRAGMA user_version"), 10300);
    EXPECT_EQ(db->queryInt("SELECT COUNT(*) FROM gpkg_extensions WHERE extension_name = "
                           "'kiosk_tile_stats'"),
              1);
    EXPECT_EQ(db->queryInt("SELECT COUNT(*) FROM gpkg_2d_gridded_tile_ancillary"), 5);
    EXPECT_EQ(db->queryInt("SELECT COUNT(*) FROM gpkg_tile_matrix WHERE table_name = 'elevation'"),
              2);
}

TEST(StoreReader, CorruptTileIsAnErrorForThatTileOnly) {
    const fs::path p = writeSmallStore("corrupt.gpkg");
    {
        auto db = SqliteDb::open(p, SqliteDb::Mode::ReadWrite);
        ASSERT_TRUE(db.ok());
        EXPECT_FALSE(db->exec("UPDATE elevation SET tile_data = x'89504E470D0A1A0A0000' WHERE "
                              "zoom_level = 1 AND tile_column = 1 AND tile_row = 0")
                         .hasErrors());
    }
    auto r = StoreReader::open(p);
    ASSERT_TRUE(r.ok());
    auto bad = (*r)->readElevation("elevation", TileId{1, 1, 0});
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.diagnostics.firstError()->code, "STORE_TILE_CORRUPT");
    EXPECT_EQ(bad.diagnostics.firstError()->where, "elevation/1/1/0");
    EXPECT_EQ(bad.diagnostics.firstError()->file, p.string());
    EXPECT_TRUE((*r)->readElevation("elevation", TileId{1, 0, 0}).ok());
    EXPECT_TRUE((*r)->readElevation("elevation", TileId{1, 1, 1}).ok());
}

struct BadRead {
    const char* name;
    const char* layer;
    TileId id;
    const char* code;
    const char* message;
};

TEST(StoreReader, BadRequestsTable) {
    const fs::path p = writeSmallStore("bad.gpkg");
    auto r = StoreReader::open(p);
    ASSERT_TRUE(r.ok());
    const BadRead cases[] = {
        {"missing tile", "elevation", {1, 3, 3}, "STORE_TILE_MISSING", "tile not in store"},
        {"unknown layer",
         "elevatoin",
         {0, 0, 0},
         "STORE_LAYER_UNKNOWN",
         "did you mean 'elevation'"},
        {"imagery as elevation", "imagery", {1, 0, 0}, "STORE_LAYER_UNKNOWN", "no elevation layer"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        auto t = (*r)->readElevation(c.layer, c.id);
        ASSERT_FALSE(t.ok());
        EXPECT_EQ(t.diagnostics.firstError()->code, c.code);
        EXPECT_NE(t.diagnostics.firstError()->format().find(c.message), std::string::npos)
            << t.diagnostics.format();
    }
    auto f = (*r)->readSequenceFrame("flood", 0, TileId{0, 0, 0});
    ASSERT_FALSE(f.ok());
    EXPECT_EQ(f.diagnostics.firstError()->code, "STORE_LAYER_UNKNOWN");
}

TEST(StoreReader, OpenErrorsNameTheFile) {
    auto missing = StoreReader::open(tempPath("does-not-exist.gpkg"));
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.diagnostics.firstError()->code, "STORE_OPEN");

    const fs::path plain = tempPath("plain.sqlite");
    {
        auto db = SqliteDb::open(plain, SqliteDb::Mode::Create);
        ASSERT_TRUE(db.ok());
        EXPECT_FALSE(db->exec("CREATE TABLE t (a)").hasErrors());
    }
    auto notOurs = StoreReader::open(plain);
    ASSERT_FALSE(notOurs.ok());
    EXPECT_EQ(notOurs.diagnostics.firstError()->code, "STORE_NOT_GEOKIOSK");
    EXPECT_NE(notOurs.diagnostics.format().find(plain.string()), std::string::npos);

    const fs::path text = tempPath("text.gpkg");
    {
        std::FILE* f = std::fopen(text.c_str(), "w");
        std::fputs("hello, not sqlite at all, really not", f);
        std::fclose(f);
    }
    auto garbage = StoreReader::open(text);
    ASSERT_FALSE(garbage.ok());
    EXPECT_TRUE(garbage.diagnostics.has("STORE_OPEN") ||
                garbage.diagnostics.has("STORE_NOT_GEOKIOSK"))
        << garbage.diagnostics.format();
}

TEST(StoreReader, ReadsWhileAnotherConnectionAppendsInWalMode) {
    const fs::path p = writeSmallStore("wal.gpkg");
    auto writer = SqliteDb::open(p, SqliteDb::Mode::ReadWrite);
    ASSERT_TRUE(writer.ok());
    EXPECT_FALSE(writer->exec("PRAGMA journal_mode=WAL").hasErrors());
    auto r = StoreReader::open(p);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_FALSE(writer
                     ->exec("CREATE TABLE IF NOT EXISTS scratch (a); BEGIN; INSERT INTO scratch "
                            "VALUES (1)")
                     .hasErrors());
    // A writer holds an open transaction: the reader still reads committed tiles.
    EXPECT_TRUE((*r)->readElevation("elevation", TileId{1, 0, 0}).ok());
    EXPECT_FALSE(writer->exec("COMMIT").hasErrors());
    EXPECT_TRUE((*r)->readElevation("elevation", TileId{1, 1, 1}).ok());
}
