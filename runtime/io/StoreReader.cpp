#include "runtime/io/StoreReader.h"

#include "runtime/core/Strings.h"
#include "runtime/io/ImageHeader.h"
#include "runtime/io/SqliteDb.h"
#include "runtime/io/StoreSchema.h"
#include "runtime/io/StoreTables.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <set>
#include <system_error>

namespace kiosk::io {

namespace {

std::atomic<std::int64_t> gPageCacheBytes{StoreReader::kDefaultPageCacheBytes};
std::atomic<int> gConnections{0};

class SqliteStoreReader final : public StoreReader {
public:
    explicit SqliteStoreReader(SqliteDb db) : mDb(std::move(db)), mQueries(mDb) { ++gConnections; }
    ~SqliteStoreReader() override { --gConnections; }
    SqliteStoreReader(const SqliteStoreReader&) = delete;
    SqliteStoreReader& operator=(const SqliteStoreReader&) = delete;

    Diagnostics load(const std::filesystem::path& path);

    const StoreInfo& info() const noexcept override { return mInfo; }

    Result<RasterTile> readElevation(const std::string& layer, const TileId& id) override {
        return readScalar(layer, id, LayerKind::Elevation);
    }

    Result<ImageTile> readImagery(const std::string& layer, const TileId& id) override {
        const LayerInfo* l = mInfo.findLayer(layer);
        if (!l || l->kind != LayerKind::Imagery) return unknownLayer(layer, "imagery layer");
        return mQueries.readImage(layer, id, mNormalMaps.count(layer) != 0);
    }

    Result<RasterTile> readSequenceFrame(const std::string& sequence, int frame,
                                         const TileId& id) override {
        auto it = mFrameTables.find(sequence);
        if (it == mFrameTables.end()) return unknownLayer(sequence, "sequence");
        if (frame < 0 || std::size_t(frame) >= it->second.size()) {
            Diagnostics d;
            d.error("STORE_FRAME_RANGE", mInfo.path, sequence,
                    "frame " + std::to_string(frame) + " out of range (sequence has " +
                        std::to_string(it->second.size()) + " frames)");
            return d;
        }
        return readScalar(it->second[std::size_t(frame)], id, LayerKind::Sequence);
    }

    std::optional<TileStats> tileStats(const std::string& layer, const TileId& id) override {
        return mQueries.stats(layer, id);
    }

    Result<bool> readTileMesh(const std::string& layer, const TileId& id, double tolerance,
                              double baseTolerance, TileMeshRow& out) override {
        if (!mHasMeshes) return false;
        return mQueries.readMesh(layer, id, tolerance, baseTolerance, out);
    }

    Result<bool> readTileTexture(const std::string& layer, const TileId& id, TextureFormat format,
                                 CompressedImage& out) override {
        if (!mHasTextures) return false;
        const LayerInfo* l = mInfo.findLayer(layer);
        if (!l || l->kind != LayerKind::Imagery) return false;  // values are never compressed
        return mQueries.readTexture(layer, id, format, out);
    }

    Result<bool> readTileTin(const std::string& layer, const TileId& id, double tolerance,
                             TileTinRow& out) override {
        if (!mHasTins) return false;
        return mQueries.readTin(layer, id, tolerance, out);
    }

private:
    Diagnostics unknownLayer(const std::string& name, const char* what) const {
        Diagnostics d;
        auto& e = d.error("STORE_LAYER_UNKNOWN", mInfo.path, name,
                          std::string("no ") + what + " of that name in the store");
        std::vector<std::string> names;
        for (const auto& l : mInfo.layers) names.push_back(l.name);
        for (const auto& s : mInfo.sequences) names.push_back(s.name);
        if (auto m = closestMatch(name, names)) e.hint = "did you mean '" + *m + "'?";
        return d;
    }

    Result<RasterTile> readScalar(const std::string& table, const TileId& id, LayerKind kind) {
        auto it = mMeta.find(table);
        const LayerInfo* l = mInfo.findLayer(table);
        if (it == mMeta.end() || !l || l->kind != kind)
            return unknownLayer(
                table, kind == LayerKind::Elevation ? "elevation layer" : "sequence frame");
        return mQueries.readScalar(table, it->second, id);
    }

    SqliteDb mDb;
    TileQueries mQueries;
    StoreInfo mInfo;
    std::map<std::string, TileQueries::ScalarMeta> mMeta;
    std::map<std::string, std::vector<std::string>> mFrameTables;
    bool mHasMeshes = false;    // kiosk_tile_meshes exists (stores imported since issue 20)
    bool mHasTins = false;      // kiosk_tile_tins exists (import breaklines / model-mesh)
    bool mHasTextures = false;  // kiosk_tile_textures exists (import textures)

    std::set<std::string> mNormalMaps;  // imagery declared RGB (kiosk_layers.description)
};

Diagnostics SqliteStoreReader::load(const std::filesystem::path& path) {
    Diagnostics d;
    mInfo.path = path.string();
    std::error_code ec;
    mInfo.sizeBytes = std::int64_t(std::filesystem::file_size(path, ec));
    if (ec) mInfo.sizeBytes = 0;
    const auto appId = mDb.queryInt("PRAGMA application_id");
    if (!appId) {
        d.add(mDb.error("STORE_OPEN", "", "cannot read the file as SQLite"));
        return d;
    }
    // A small page cache: tiles are blobs read once each (their pages would only duplicate
    // what the tile cache holds decoded); the b-tree pages that lead to them fit in 256 KiB.
    // SQLite's default is 2 MiB per connection (docs/performance.md). A kiosk may set its own.
    const std::int64_t cacheKiB = std::max<std::int64_t>(gPageCacheBytes.load() / 1024, 1);
    d.append(mDb.exec("PRAGMA cache_size=-" + std::to_string(cacheKiB)));
    if (auto c = mDb.queryInt("PRAGMA cache_size"))  // negative: KiB; positive: pages
        mInfo.pageCacheBytes =
            *c < 0 ? -*c * 1024 : *c * mDb.queryInt("PRAGMA page_size").value_or(4096);
    if (*appId != kGpkgApplicationId || !mDb.tableExists(kGridTable) ||
        !mDb.tableExists(kLayersTable)) {
        d.error("STORE_NOT_GEOKIOSK", mInfo.path, "",
                *appId != kGpkgApplicationId
                    ? "not a GeoPackage (application_id is not 'GPKG')"
                    : "GeoPackage without geokiosk tables (import it with 'geokiosk import')");
        return d;
    }
    // Before any query names a column: drift is one line, not a "no such column" per tile.
    d.append(checkStoreSchema(mDb));
    if (d.hasErrors()) return d;
    auto g = mDb.prepare(
        "SELECT g.srs_id, g.min_x, g.min_y, g.max_x, g.max_y, g.tile_width, g.tile_height, "
        "g.levels, g.finest_pixel_size, s.srs_name, s.definition FROM kiosk_grid g LEFT JOIN "
        "gpkg_spatial_ref_sys s ON s.srs_id = g.srs_id WHERE g.id = 1");
    if (!g) return g.diagnostics;
    if (g->step() != SQLITE_ROW) {
        d.error("STORE_NOT_GEOKIOSK", mInfo.path, kGridTable, "store has no tile grid");
        return d;
    }
    TileGrid& grid = mInfo.grid;
    grid.srsId = int(g->columnInt(0));
    grid.minX = g->columnDouble(1);
    grid.minY = g->columnDouble(2);
    grid.maxX = g->columnDouble(3);
    grid.maxY = g->columnDouble(4);
    const int tw = int(g->columnInt(5)), th = int(g->columnInt(6)), levels = int(g->columnInt(7));
    const double finest = g->columnDouble(8);
    grid.crsName = g->columnText(9);
    grid.crsWkt = g->columnText(10);
    if (levels < 1 || levels > 30 || tw < 1 || th < 1 || tw > 4096 || th > 4096 || !(finest > 0)) {
        d.error("STORE_NOT_GEOKIOSK", mInfo.path, kGridTable, "tile grid is invalid");
        return d;
    }
    grid.setPyramid(levels, tw, th, finest);

    auto ls = mDb.prepare(
        "SELECT l.table_name, l.kind, l.units, l.min_value, l.max_value, l.nodata, "
        "l.data_min_x, l.data_min_y, l.data_max_x, l.data_max_y, l.levels, l.tile_count, "
        "a.scale, a.offset, a.data_null, l.precision, l.description FROM kiosk_layers l "
        "LEFT JOIN gpkg_2d_gridded_coverage_ancillary a ON a.tile_matrix_set_name = l.table_name "
        "ORDER BY l.rowid");
    if (!ls) return ls.diagnostics;
    while (ls->step() == SQLITE_ROW) {
        LayerInfo li;
        li.name = ls->columnText(0);
        const auto kind = parseLayerKind(ls->columnText(1));
        if (!kind) {
            d.warning("STORE_LAYER_KIND", mInfo.path, li.name,
                      "unknown layer kind '" + ls->columnText(1) + "', layer ignored");
            continue;
        }
        li.kind = *kind;
        li.units = ls->columnText(2);
        li.minValue = ls->columnDouble(3);
        li.maxValue = ls->columnDouble(4);
        if (!ls->columnIsNull(5)) li.nodata = ls->columnDouble(5);
        li.dataMinX = ls->columnDouble(6);
        li.dataMinY = ls->columnDouble(7);
        li.dataMaxX = ls->columnDouble(8);
        li.dataMaxY = ls->columnDouble(9);
        li.levels = int(ls->columnInt(10));
        li.tileCount = ls->columnInt(11);
        li.precision = ls->columnIsNull(15) ? 0.0 : ls->columnDouble(15);
        if (li.kind == LayerKind::Imagery && declaresNormalMap(ls->columnText(16)))
            mNormalMaps.insert(li.name);
        if (li.kind != LayerKind::Imagery) {
            TileQueries::ScalarMeta meta;
            meta.tileWidth = tw;
            meta.tileHeight = th;
            meta.coverageScale = ls->columnIsNull(12) ? 1.0 : ls->columnDouble(12);
            meta.coverageOffset = ls->columnIsNull(13) ? 0.0 : ls->columnDouble(13);
            meta.dataNull = ls->columnIsNull(14) ? 65535.0 : ls->columnDouble(14);
            mMeta[li.name] = meta;
        }
        mInfo.layers.push_back(std::move(li));
    }

    // Scalar tiles cannot be drawn right without these: a clear error, not vanishing terrain.
    if (!mMeta.empty())
        for (const char* t : {kTileStatsTable, "gpkg_2d_gridded_tile_ancillary"})
            if (!mDb.tableExists(t)) {
                d.error("STORE_NOT_GEOKIOSK", mInfo.path, t,
                        "table is missing (scalar layers need it)");
                return d;
            }
    mHasMeshes = mDb.tableExists(kTileMeshesTable);
    mHasTins = mDb.tableExists(kTileTinsTable);
    mHasTextures = mDb.tableExists(kTileTexturesTable);

    if (mDb.tableExists(kSequencesTable)) {
        auto ss = mDb.prepare(
            "SELECT name, units, variable, categorical, nodata FROM "
            "kiosk_sequences ORDER BY rowid");
        auto fs = mDb.prepare(
            "SELECT time_epoch, table_name, min_value, max_value, frame_index FROM "
            "kiosk_sequence_frames WHERE sequence_name = ? ORDER BY "
            "frame_index");
        if (!ss) return ss.diagnostics;
        if (!fs) return fs.diagnostics;
        while (ss->step() == SQLITE_ROW) {
            SequenceInfo si;
            si.name = ss->columnText(0);
            si.units = ss->columnText(1);
            si.variable = ss->columnText(2);
            si.categorical = ss->columnInt(3) != 0;
            if (!ss->columnIsNull(4)) si.nodata = ss->columnDouble(4);
            si.levels = levels;
            fs->reset();
            fs->bind(1, std::string_view(si.name));
            auto& tables = mFrameTables[si.name];
            while (fs->step() == SQLITE_ROW) {
                // Deleted frame rows would otherwise replay as a shorter, wrong sequence.
                const std::int64_t index = fs->columnInt(4);
                const double time = fs->columnDouble(0);
                if (index != std::int64_t(si.frameTimes.size()) ||
                    (!si.frameTimes.empty() && !(time > si.frameTimes.back()))) {
                    d.error("STORE_NOT_GEOKIOSK", mInfo.path,
                            std::string(kFramesTable) + "/" + si.name,
                            index != std::int64_t(si.frameTimes.size())
                                ? "frame " + std::to_string(si.frameTimes.size()) +
                                      " is missing (next is " + std::to_string(index) + ")"
                                : "frame " + std::to_string(index) +
                                      " is not later than the one before");
                    return d;
                }
                si.frameTimes.push_back(fs->columnDouble(0));
                tables.push_back(fs->columnText(1));
                si.frameMin.push_back(fs->columnDouble(2));
                si.frameMax.push_back(fs->columnDouble(3));
            }
            mInfo.sequences.push_back(std::move(si));
        }
    }
    return d;
}

}  // namespace

void StoreReader::setPageCacheBytes(std::int64_t bytes) {
    gPageCacheBytes = bytes > 0 ? bytes : kDefaultPageCacheBytes;
}

std::int64_t StoreReader::pageCacheBytes() {
    return gPageCacheBytes.load();
}

int StoreReader::openConnections() {
    return gConnections.load();
}

Result<std::unique_ptr<StoreReader>> StoreReader::open(const std::filesystem::path& path) {
    Diagnostics d;
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!std::filesystem::is_regular_file(status)) {
        // A folder, FIFO or device (/dev/zero) is named as what it is: SQLite would block on a
        // FIFO and "does not exist" would send the user looking for the wrong problem.
        d.error("STORE_OPEN", path.string(), "",
                !std::filesystem::exists(status)        ? "store file does not exist"
                : std::filesystem::is_directory(status) ? "is a folder, not a store file"
                                                        : "is not a regular file (a device, FIFO "
                                                          "or socket), not a store file");
        return d;
    }
    auto db = SqliteDb::open(path, SqliteDb::Mode::ReadOnly);
    if (!db) return db.diagnostics;
    auto reader = std::make_unique<SqliteStoreReader>(std::move(*db));
    d = reader->load(path);
    if (d.hasErrors()) return d;
    return Result<std::unique_ptr<StoreReader>>(std::unique_ptr<StoreReader>(std::move(reader)),
                                                std::move(d));
}

}  // namespace kiosk::io
