// Local TINs in the grid (issue 20, Baumann et al. 2000): `import breaklines` builds CGAL
// constrained Delaunay TINs for the tiles a levee crosses; the loader draws them instead of the
// grid mesh, with the tile's border posts exactly; a damaged TIN falls back to the grid with one
// warning; bad inputs give one line and exit status 1.
#include "runtime/app/LocalTinCommand.h"
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreIntegrity.h"
#include "runtime/loader/StoreTileLoader.h"
#include "tests/support/LeveeFixture.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <gdal.h>
#include <ogr_api.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import::test;
namespace levee = kiosk::test::levee;

namespace {

std::int64_t queryInt(const fs::path& store, const std::string& sql) {
    auto db = io::SqliteDb::open(store, io::SqliteDb::Mode::ReadOnly);
    EXPECT_TRUE(db.ok());
    return db->queryInt(sql).value_or(-1);
}

struct CliRun {
    int status = 0;
    std::string err;
};

CliRun cli(const std::string& kind, const std::vector<std::string>& args) {
    ::testing::internal::CaptureStderr();
    CliRun r;
    r.status = app::runImportLocalTins(kind, args);
    r.err = ::testing::internal::GetCapturedStderr();
    return r;
}

int lines(const std::string& s) {
    int n = 0;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) n += !l.empty();
    return n;
}

fs::path leveeStore(const fs::path& dir) {
    const fs::path store = dir / "levee.gpkg";
    const Diagnostics d = import::importElevation(levee::writeDem(dir).string(), options(store));
    EXPECT_FALSE(d.hasErrors()) << d.format();
    return store;
}

terrain::TilePayload load(const fs::path& store, const TileId& id, int tier = 0,
                          const terrain::TerrainOptions& options = {}) {
    loader::StoreTileLoader l([store] { return io::StoreReader::open(store); },
                              {{"elevation", io::LayerKind::Elevation}}, options);
    l.threadStarted();
    loader::LoadRequest req;
    req.key.id = id;
    req.key.frame = tier;  // an elevation key's frame is its tolerance tier
    terrain::TilePayload p = l.load(req);
    l.threadStopping();
    return p;
}

// The TIN's surface at world (x, y): the surface triangle holding it (triangles bucketed by
// their bounding boxes over post cells). Unlike terrain::MeshPosts it also finds long thin
// triangles that cover no post.
class TinSurface {
public:
    explicit TinSurface(const terrain::TileMesh& m) : mMesh(m), mN(m.postIntervals) {
        mCells.resize(std::size_t(mN) * std::size_t(mN));
        for (std::uint32_t t = 0; t < m.surfaceIndexCount; t += 3) {
            double lo[2] = {1e30, 1e30}, hi[2] = {-1e30, -1e30};
            for (int k = 0; k < 3; ++k) {
                const glm::dvec2 p = post(m.indices[t + std::uint32_t(k)]);
                for (int c = 0; c < 2; ++c)
                    lo[c] = std::min(lo[c], p[c]), hi[c] = std::max(hi[c], p[c]);
            }
            for (int j = std::max(0, int(lo[1])); j <= std::min(mN - 1, int(hi[1])); ++j)
                for (int i = std::max(0, int(lo[0])); i <= std::min(mN - 1, int(hi[0])); ++i)
                    mCells[std::size_t(j) * std::size_t(mN) + std::size_t(i)].push_back(t);
        }
    }
    bool at(double x, double y, double& z) const {
        const glm::dvec2 q((x - mMesh.origin.x) / mMesh.postSpacing.x - 0.5,
                           (mMesh.origin.y - y) / mMesh.postSpacing.y - 0.5);
        const int i = std::clamp(int(q.x), 0, mN - 1), j = std::clamp(int(q.y), 0, mN - 1);
        for (std::uint32_t t : mCells[std::size_t(j) * std::size_t(mN) + std::size_t(i)]) {
            const glm::dvec2 a = post(mMesh.indices[t]), b = post(mMesh.indices[t + 1]),
                             c = post(mMesh.indices[t + 2]);
            const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
            const double wb = ((q.x - a.x) * (c.y - a.y) - (c.x - a.x) * (q.y - a.y)) / det;
            const double wc = ((b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y)) / det;
            if (wb < -1e-7 || wc < -1e-7 || wb + wc > 1 + 1e-7) continue;
            const double za = height(mMesh.indices[t]), zb = height(mMesh.indices[t + 1]),
                         zc = height(mMesh.indices[t + 2]);
            z = za + wb * (zb - za) + wc * (zc - za);
            return true;
        }
        return false;
    }

private:
    glm::dvec2 post(std::uint32_t v) const {
        const float* f = &mMesh.vertices[v * terrain::TileMesh::kFloatsPerVertex];
        return {f[0] / mMesh.postSpacing.x - 0.5, -f[1] / mMesh.postSpacing.y - 0.5};
    }
    double height(std::uint32_t v) const {
        return mMesh.vertices[v * terrain::TileMesh::kFloatsPerVertex + 2];
    }
    const terrain::TileMesh& mMesh;
    int mN;
    std::vector<std::vector<std::uint32_t>> mCells;
};

// The finest-level tile holding the crest's midpoint.
TileId midTile(io::StoreReader& r) {
    const io::TileGrid& g = r.info().grid;
    const io::TileMatrix& m = g.levels.back();
    const double x = 0.5 * (levee::kAx + levee::kBx), y = 0.5 * (levee::kAy + levee::kBy);
    return TileId{g.maxLevel(), int((x - g.minX) / (m.pixelXSize * m.tileWidth)),
                  int((g.maxY - y) / (m.pixelYSize * m.tileHeight))};
}

TEST(LocalTinImport, LeveeBreaklineBecomesTheTinOfTheTilesItCrosses) {
    const fs::path dir = freshTestDir("geokiosk-local-tin");
    const fs::path store = leveeStore(dir);
    const CliRun r = cli("breaklines", {levee::writeCrest(dir, true).string(), "--store",
                                        store.string(), "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GE(queryInt(store, "SELECT COUNT(*) FROM kiosk_tile_tins WHERE source = 'crest'"), 2);
    EXPECT_EQ(queryInt(store,
                       "SELECT COUNT(*) FROM gpkg_extensions WHERE table_name = "
                       "'kiosk_tile_tins' AND extension_name = 'kiosk_tile_tins'"),
              1);
    const Diagnostics deep = io::checkStoreIntegrity(store, io::IntegrityLevel::Deep);
    EXPECT_FALSE(deep.hasErrors()) << deep.format();

    auto reader = openStore(store);
    ASSERT_TRUE(reader);
    const TileId id = midTile(*reader);
    const terrain::TilePayload p = load(store, id);
    ASSERT_EQ(p.status, terrain::TilePayload::Status::Ready) << p.diagnostics.format();
    ASSERT_TRUE(p.mesh);
    EXPECT_TRUE(p.diagnostics.empty()) << p.diagnostics.format();
    const terrain::TileMesh& mesh = *p.mesh;
    EXPECT_EQ(mesh.cellLevels, 0);
    EXPECT_GT(mesh.skirtTriangleCount(), 0u);
    auto posts = reader->readElevation("elevation", id);
    ASSERT_TRUE(posts.ok());
    const int n = posts->postsX - 1;
    const double px = mesh.postSpacing.x, py = mesh.postSpacing.y;
    int border = 0, onCrest = 0;
    for (std::size_t v = 0; v < mesh.surfaceVertexCount; ++v) {
        const float* f = &mesh.vertices[v * terrain::TileMesh::kFloatsPerVertex];
        const double u = f[0] / px - 0.5, w = -f[1] / py - 0.5;
        const int i = int(std::lround(u)), j = int(std::lround(w));
        const bool onPost = std::abs(u - i) < 1e-4 && std::abs(w - j) < 1e-4;
        if (onPost && (i == 0 || j == 0 || i == n || j == n)) {
            // The seam with the neighbouring grid tiles: the border posts, bit for bit.
            ++border;
            EXPECT_EQ(f[2], posts->at(i, j)) << "border post " << i << "," << j;
            continue;
        }
        if (onPost) continue;
        // Every vertex between posts is on the breakline, at the line's height.
        const double x = mesh.origin.x + f[0], y = mesh.origin.y + f[1];
        EXPECT_LT(levee::crestDistance(x, y), 2e-3) << "vertex " << v << " off the line";
        EXPECT_NEAR(f[2], levee::crestHeight(x, y), 2e-3);
        ++onCrest;
    }
    EXPECT_EQ(border, 4 * n) << "every border post is a TIN vertex";
    EXPECT_GE(onCrest, 2);
    // A coarser tolerance tier draws the same TIN (the only one stored); a finer tolerance
    // than the TIN's (the full-resolution reference) draws the grid.
    const terrain::TilePayload far = load(store, id, 3);
    ASSERT_TRUE(far.mesh) << far.diagnostics.format();
    EXPECT_EQ(far.mesh->surfaceTriangleCount(), mesh.surfaceTriangleCount());
    EXPECT_GT(far.mesh->skirtDepth, mesh.skirtDepth);
    const terrain::TilePayload full =
        load(store, id, 0, terrain::TerrainOptions::fullResolutionReference());
    ASSERT_TRUE(full.mesh) << full.diagnostics.format();
    EXPECT_GT(full.mesh->cellLevels, 0) << "the grid mesh";
    // Away from the line every post is within the tile's tolerance of the TIN, and along the
    // line the TIN is the crest while the grid (the posts) cuts it off.
    const TinSurface surface(mesh);
    double worstPost = 0, crestGap = 0;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = mesh.origin.x + (i + 0.5) * px, y = mesh.origin.y - (j + 0.5) * py;
            if (levee::crestDistance(x, y) < 1.5 * px) continue;
            double h;
            ASSERT_TRUE(surface.at(x, y, h));
            worstPost = std::max(worstPost, std::abs(h - posts->at(i, j)));
        }
    EXPECT_LE(worstPost, mesh.tolerance + 1e-4);
    for (int k = 0; k <= 100; ++k) {
        const double t = 0.3 + 0.4 * k / 100.0;  // the middle of the crest
        const double x = levee::kAx + t * (levee::kBx - levee::kAx),
                     y = levee::kAy + t * (levee::kBy - levee::kAy);
        double h;
        if (!surface.at(x, y, h)) continue;  // in another tile
        // Within half a post of the border the TIN is the border posts' (the seam), not the line.
        const double bu = (x - mesh.origin.x) / px - 0.5, bv = (mesh.origin.y - y) / py - 0.5;
        if (std::min({bu, bv, n - bu, n - bv}) < 0.6) continue;
        EXPECT_NEAR(h, levee::crestHeight(x, y), 2e-3);
        const double gu = (x - mesh.origin.x) / px - 0.5, gv = (mesh.origin.y - y) / py - 0.5;
        const int gi = int(gu), gj = int(gv);
        const double fu = gu - gi, fv = gv - gj;
        const double grid =
            (posts->at(gi, gj) * (1 - fu) + posts->at(gi + 1, gj) * fu) * (1 - fv) +
            (posts->at(gi, gj + 1) * (1 - fu) + posts->at(gi + 1, gj + 1) * fu) * fv;
        crestGap = std::max(crestGap, levee::crestHeight(x, y) - grid);
    }
    EXPECT_GT(crestGap, 0.2) << "the grid should cut the crest off (else the test shows nothing)";
}

TEST(LocalTinImport, FlatLinesTakeTheirHeightsFromTheElevation) {
    const fs::path dir = freshTestDir("geokiosk-local-tin");
    const fs::path store = leveeStore(dir);
    const CliRun r = cli("breaklines", {levee::writeCrest(dir, false).string(), "--store",
                                        store.string(), "--name", "crest2d", "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    auto reader = openStore(store);
    ASSERT_TRUE(reader);
    const TileId id = midTile(*reader);
    const terrain::TilePayload p = load(store, id);
    ASSERT_TRUE(p.mesh) << p.diagnostics.format();
    auto posts = reader->readElevation("elevation", id);
    ASSERT_TRUE(posts.ok());
    const double px = p.mesh->postSpacing.x;
    int checked = 0;
    for (std::size_t v = 0; v < p.mesh->surfaceVertexCount; ++v) {
        const float* f = &p.mesh->vertices[v * terrain::TileMesh::kFloatsPerVertex];
        const double u = f[0] / px - 0.5, w = -f[1] / px - 0.5;
        if (std::abs(u - std::round(u)) < 1e-4 && std::abs(w - std::round(w)) < 1e-4) continue;
        // Where the line is cut at the tile's border the height is interpolated along the line.
        const int n = p.mesh->postIntervals;
        if (std::min({u, w, n - u, n - w}) < 0.6) continue;
        // A line vertex: the posts' bilinear height there (densified every post spacing).
        const int i = int(u), j = int(w);
        const double fu = u - i, fv = w - j;
        const double z = (posts->at(i, j) * (1 - fu) + posts->at(i + 1, j) * fu) * (1 - fv) +
                         (posts->at(i, j + 1) * (1 - fu) + posts->at(i + 1, j + 1) * fu) * fv;
        EXPECT_NEAR(f[2], z, 2e-3) << "vertex " << v;
        ++checked;
    }
    EXPECT_GT(checked, 100) << "a 2D line is densified to one vertex per post spacing";
}

TEST(LocalTinImport, DamagedTinDrawsTheGridAndIsNamed) {
    const fs::path dir = freshTestDir("geokiosk-local-tin");
    const fs::path store = leveeStore(dir);
    ASSERT_EQ(cli("breaklines",
                  {levee::writeCrest(dir, true).string(), "--store", store.string(), "--quiet"})
                  .status,
              0);
    auto reader = openStore(store);
    ASSERT_TRUE(reader);
    const TileId id = midTile(*reader);
    reader.reset();
    {
        auto db = io::SqliteDb::open(store, io::SqliteDb::Mode::ReadWrite);
        ASSERT_TRUE(db.ok());
        ASSERT_FALSE(db->exec("UPDATE kiosk_tile_tins SET tin = substr(tin, 1, 40) WHERE "
                              "zoom_level = " +
                              std::to_string(id.level) +
                              " AND tile_column = " + std::to_string(id.column) +
                              " AND tile_row = " + std::to_string(id.row) + " AND tier = 0")
                         .hasErrors());
    }
    const terrain::TilePayload p = load(store, id);
    ASSERT_EQ(p.status, terrain::TilePayload::Status::Ready);
    ASSERT_TRUE(p.mesh);
    EXPECT_GT(p.mesh->cellLevels, 0) << "the grid mesh, not a TIN";
    ASSERT_EQ(p.diagnostics.size(), 1u) << p.diagnostics.format();
    const Diagnostic& w = p.diagnostics.items()[0];
    EXPECT_EQ(w.severity, Severity::Warning);
    EXPECT_EQ(w.code, "STORE_TIN_CORRUPT");
    const std::string tile =
        std::to_string(id.level) + "/" + std::to_string(id.column) + "/" + std::to_string(id.row);
    EXPECT_EQ(w.where, "elevation/" + tile + " tier 0") << w.format();
    const Diagnostics deep = io::checkStoreIntegrity(store, io::IntegrityLevel::Deep);
    ASSERT_EQ(deep.size(), 1u) << deep.format();
    EXPECT_EQ(deep.items()[0].code, "STORE_TIN_CORRUPT");
    EXPECT_EQ(deep.items()[0].where, "elevation/" + tile + " tier 0");
}

// A GeoPackage line layer without a CRS (GeoJSON always has one: WGS 84 unless it names another).
fs::path linesWithoutCrs(const fs::path& dir) {
    GDALAllRegister();
    const fs::path p = dir / "nocrs.gpkg";
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GPKG"), p.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
    OGRLayerH layer = GDALDatasetCreateLayer(ds, "lines", nullptr, wkbLineString, nullptr);
    OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(layer));
    OGRGeometryH g = nullptr;
    char wkt[] = "LINESTRING (550060 5199930, 550420 5199670)";
    char* text = wkt;
    OGR_G_CreateFromWkt(&text, nullptr, &g);
    OGR_F_SetGeometryDirectly(f, g);
    EXPECT_EQ(OGR_L_CreateFeature(layer, f), OGRERR_NONE);
    OGR_F_Destroy(f);
    GDALClose(ds);
    return p;
}

TEST(LocalTinImport, BadLinesGiveOneLineAndExitOne) {
    const fs::path dir = freshTestDir("geokiosk-local-tin");
    const fs::path store = leveeStore(dir);
    std::ofstream(dir / "broken.geojson") << "{ \"type\": \"FeatureCollection\", \"features\": [ {";
    std::ofstream(dir / "outside.geojson")
        << R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32610"}},)"
        << R"("features":[{"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[650000,5300000,1],[650100,5300100,1]]}}]})";
    std::ofstream(dir / "polygon.geojson")
        << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[-122.3,46.9],[-122.2,46.9],[-122.2,47.0],[-122.3,46.9]]]}}]})";
    const struct {
        fs::path file;
        const char* code;
    } cases[] = {{dir / "broken.geojson", "IMPORT_UNREADABLE"},
                 {linesWithoutCrs(dir), "IMPORT_NO_CRS"},
                 {dir / "outside.geojson", "IMPORT_TIN_OUTSIDE"},
                 {dir / "polygon.geojson", "IMPORT_BREAKLINES"},
                 {dir / "missing.geojson", "IMPORT_UNREADABLE"}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.file.filename().string());
        const CliRun r = cli("breaklines", {c.file.string(), "--store", store.string(), "--quiet"});
        EXPECT_EQ(r.status, 1);
        EXPECT_EQ(lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(c.code), std::string::npos) << r.err;
    }
    // Nothing was written: the store has no TIN table.
    EXPECT_EQ(queryInt(store, "SELECT COUNT(*) FROM sqlite_master WHERE name = 'kiosk_tile_tins'"),
              0);
    EXPECT_EQ(cli("breaklines", {"x.geojson"}).status, 2);
    EXPECT_EQ(cli("breaklines", {"x.geojson", "--store", store.string(), "--name", "a b"}).status,
              2);
}

}  // namespace
