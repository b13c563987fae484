#include "runtime/import/LocalTins.h"

#include "runtime/import/TileTin.h"
#include "runtime/io/TinBlob.h"
#include "runtime/terrain/RtinMesher.h"
#include "runtime/terrain/TerrainOptions.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <thread>

namespace kiosk::import {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
// Posts this close (post intervals) to a line are left out of its TIN: their heights would
// notch the line (a post beside a sharp crest is lower than the crest line through it).
constexpr double kClearance = 1.0;
constexpr double kSampleStep = 0.25;  // post intervals between deviation samples

double bilinear(const io::RasterTile& t, double u, double v) {
    const int n = t.postsX - 1;
    if (u < 0 || v < 0 || u > n || v > n) return kNan;
    const int i = std::min(int(u), n - 1), j = std::min(int(v), n - 1);
    const double fu = u - i, fv = v - j;
    const double a = t.at(i, j), b = t.at(i + 1, j), c = t.at(i, j + 1), d = t.at(i + 1, j + 1);
    return (a * (1 - fu) + b * fu) * (1 - fv) + (c * (1 - fu) + d * fu) * fv;
}

double segmentDistance(double px, double py, const glm::dvec3& a, const glm::dvec3& b) {
    const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? ((px - a.x) * dx + (py - a.y) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(px - (a.x + t * dx), py - (a.y + t * dy));
}

// Where a tile's posts sit: world -> post coordinates.
struct TileFrame {
    double x0 = 0, y1 = 0, px = 1, py = 1;
    int n = 0;
    glm::dvec3 toPost(const glm::dvec3& w) const {
        return {(w.x - x0) / px - 0.5, (y1 - w.y) / py - 0.5, w.z};
    }
};

TileFrame frameOf(const io::TileGrid& grid, const TileId& id) {
    const terrain::MeshParams m = terrain::MeshParams::forTile(grid, id, {}, 0.0);
    return {m.originX, m.originY, m.pixelX, m.pixelY, grid.levels[std::size_t(id.level)].tileWidth};
}

struct TinJob {
    TileId id;
    io::RasterTile posts;
    TileTinInput input;
    const std::vector<std::uint32_t>* triangles = nullptr;  // the model's index triples
    std::size_t modelTriangles = 0;  // model triangles under the tile (bucket index below)
    std::vector<std::vector<std::uint32_t>> buckets;  // per post cell: model triangles over it
    std::vector<glm::dvec3> modelPost;                // model points in this tile's post coords
    bool needed = false;
    double tolerance = 0.0;  // tier 0
    struct Tier {
        double tolerance = 0.0;
        TileTinResult tin;
        std::vector<std::uint8_t> blob;
    };
    std::vector<Tier> tiers;  // tier 0 (kiosk_tile_tins has a tier column for coarser ones)
    Diagnostics error;
    std::size_t gridTriangles = 0;
};

bool insideTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double u,
                    double v) {
    auto side = [&](const glm::dvec3& p, const glm::dvec3& q) {
        return (q.x - p.x) * (v - p.y) - (q.y - p.y) * (u - p.x);
    };
    const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
    return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

// Whether (u, v) lies under one of the model triangles over the tile.
bool coveredBy(const TinJob& job, double u, double v) {
    const int n = job.posts.postsX - 1;
    if (job.buckets.empty() || n < 1) return false;
    const int i = std::clamp(int(std::floor(u)), 0, n - 1),
              j = std::clamp(int(std::floor(v)), 0, n - 1);
    const std::vector<std::uint32_t>& tri = *job.triangles;
    for (std::uint32_t t : job.buckets[std::size_t(j) * std::size_t(n) + std::size_t(i)])
        if (insideTriangle(job.modelPost[tri[t]], job.modelPost[tri[t + 1]],
                           job.modelPost[tri[t + 2]], u, v))
            return true;
    return false;
}

class Planner {
public:
    Planner(const io::TileGrid& grid, const TinFeatures& f) : mF(f), mGrid(grid) {}

    // Tiles of `level` whose posts (plus the clearance) the features' bounding boxes touch.
    std::set<TileId> crossedTiles(int level) const {
        std::set<TileId> out;
        const io::TileMatrix& m = mGrid.levels[std::size_t(level)];
        const double tw = m.pixelXSize * m.tileWidth, th = m.pixelYSize * m.tileHeight;
        auto add = [&](double minX, double minY, double maxX, double maxY) {
            const double pad = (kClearance + 1.0) * m.pixelXSize;
            const int c0 = std::max(0, int(std::floor((minX - pad - mGrid.minX) / tw)));
            const int c1 =
                std::min(m.matrixWidth - 1, int(std::floor((maxX + pad - mGrid.minX) / tw)));
            const int r0 = std::max(0, int(std::floor((mGrid.maxY - maxY - pad) / th)));
            const int r1 =
                std::min(m.matrixHeight - 1, int(std::floor((mGrid.maxY - minY + pad) / th)));
            for (int r = r0; r <= r1; ++r)
                for (int c = c0; c <= c1; ++c) out.insert(TileId{level, c, r});
        };
        for (const auto& line : mF.lines) {
            if (line.empty()) continue;
            double a = line[0].x, b = line[0].y, c = a, d = b;
            for (const auto& p : line) {
                a = std::min(a, p.x), b = std::min(b, p.y), c = std::max(c, p.x),
                d = std::max(d, p.y);
            }
            add(a, b, c, d);
        }
        return out;
    }

    // Clip the features to the tile, decide whether the grid misses them, fill the TIN input.
    void prepare(TinJob& job, bool always) const {
        const TileFrame f = frameOf(mGrid, job.id);
        const double e = double(job.posts.stats.geometricError);
        const terrain::TerrainOptions defaults;  // the loader's tier-0 tolerance
        job.tolerance = defaults.tinTolerance(e);
        TileTinInput& in = job.input;
        in.pixelX = f.px;
        in.pixelY = f.py;
        in.tolerance = job.tolerance;
        std::vector<TinPolyline> near;
        for (const auto& line : mF.lines) {
            TinPolyline p;
            p.reserve(line.size());
            for (const auto& w : line) p.push_back(f.toPost(w));
            clipPolyline(p, kTinBorderInset, f.n - kTinBorderInset, in.lines);
            clipPolyline(p, -kClearance, f.n + kClearance, near);
        }
        modelUnder(job, f);
        if (in.lines.empty() && job.modelTriangles == 0) return;
        // Does the grid keep the features within the tile's error bound?
        double worst = 0.0;
        for (const TinPolyline& piece : in.lines)
            for (std::size_t k = 0; k + 1 < piece.size(); ++k) {
                const glm::dvec3 a = piece[k], b = piece[k + 1];
                const int steps =
                    std::max(1, int(std::ceil(glm::length(glm::dvec2(b - a)) / kSampleStep)));
                for (int s = 0; s <= steps; ++s) {
                    const glm::dvec3 p = a + (b - a) * (double(s) / steps);
                    const double g = bilinear(job.posts, p.x, p.y);
                    if (std::isfinite(g)) worst = std::max(worst, std::abs(g - p.z));
                }
            }
        job.needed = always || worst > e + job.tolerance;
        if (!job.needed) return;
        const int size = f.n + 1;
        in.replaced.assign(std::size_t(size) * std::size_t(size), 0);
        for (const TinPolyline& piece : near)
            for (std::size_t k = 0; k + 1 < piece.size(); ++k) {
                const glm::dvec3 a = piece[k], b = piece[k + 1];
                const int i0 = std::max(0, int(std::floor(std::min(a.x, b.x) - kClearance)));
                const int i1 = std::min(f.n, int(std::ceil(std::max(a.x, b.x) + kClearance)));
                const int j0 = std::max(0, int(std::floor(std::min(a.y, b.y) - kClearance)));
                const int j1 = std::min(f.n, int(std::ceil(std::max(a.y, b.y) + kClearance)));
                for (int j = j0; j <= j1; ++j)
                    for (int i = i0; i <= i1; ++i)
                        if (segmentDistance(i, j, a, b) <= kClearance)
                            in.replaced[std::size_t(j) * std::size_t(size) + std::size_t(i)] = 1;
            }
        if (job.modelTriangles == 0) return;
        // Posts under the model mesh: the model's own triangles stand there instead.
        for (int j = 0; j <= f.n; ++j)
            for (int i = 0; i <= f.n; ++i)
                if (coveredBy(job, i, j))
                    in.replaced[std::size_t(j) * std::size_t(size) + std::size_t(i)] = 1;
        in.covered = [&job](double u, double v) { return coveredBy(job, u, v); };
    }

private:
    // The model triangles over the tile, bucketed per post cell (for the coverage test).
    void modelUnder(TinJob& job, const TileFrame& f) const {
        if (mF.meshTriangles.empty()) return;
        job.triangles = &mF.meshTriangles;
        job.modelPost.resize(mF.meshPoints.size());
        for (std::size_t i = 0; i < mF.meshPoints.size(); ++i)
            job.modelPost[i] = f.toPost(mF.meshPoints[i]);
        job.buckets.assign(std::size_t(f.n) * std::size_t(f.n), {});
        for (std::size_t t = 0; t + 2 < mF.meshTriangles.size(); t += 3) {
            const glm::dvec3& a = job.modelPost[mF.meshTriangles[t]];
            const glm::dvec3& b = job.modelPost[mF.meshTriangles[t + 1]];
            const glm::dvec3& c = job.modelPost[mF.meshTriangles[t + 2]];
            const int i0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
            const int i1 = std::min(f.n - 1, int(std::floor(std::max({a.x, b.x, c.x}))));
            const int j0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
            const int j1 = std::min(f.n - 1, int(std::floor(std::max({a.y, b.y, c.y}))));
            if (i0 > i1 || j0 > j1) continue;
            ++job.modelTriangles;
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i)
                    job.buckets[std::size_t(j) * std::size_t(f.n) + std::size_t(i)].push_back(
                        std::uint32_t(t));
        }
    }

    const TinFeatures& mF;
    const io::TileGrid& mGrid;
};

}  // namespace

namespace {

// The tile's TIN at tier 0 (the loader takes it for every coarser tier too). Coarser TINs were
// tried: their border keeps every border post, so they stayed above ~1000 triangles a tile and
// cost the import a CGAL build per tier (see docs/terrain.md "Local TINs").
void buildTiers(TinJob& job) {
    job.input.tolerance = job.tolerance;
    Result<TileTinResult> r = buildTileTin(job.input);
    if (!r) {
        job.error = std::move(r.diagnostics);
        return;
    }
    std::vector<std::uint8_t> blob = io::encodeTinBlob(r->mesh);
    job.tiers.push_back({job.tolerance, std::move(*r.value), std::move(blob)});
}

// Build the jobs' TINs on `threads` threads (the CGAL work), with the grid mesh's triangle
// count of the same tile for the comparison the import reports.
void buildJobs(std::vector<TinJob>& jobs, int threads) {
    std::vector<std::thread> pool;
    const std::size_t workers = std::size_t(std::max(1, threads));
    for (std::size_t w = 0; w < workers; ++w)
        pool.emplace_back([&, w] {
            terrain::RtinMesher mesher;
            terrain::TileMesh mesh;
            for (std::size_t j = w; j < jobs.size(); j += workers) {
                TinJob& job = jobs[j];
                if (!job.needed) continue;
                job.input.posts = &job.posts;
                buildTiers(job);
                terrain::MeshParams p;
                p.pixelX = job.input.pixelX;
                p.pixelY = job.input.pixelY;
                p.tolerance = job.tolerance;
                if (!mesher.build(job.posts, p, mesh).hasErrors())
                    job.gridTriangles = mesh.surfaceTriangleCount();
            }
        });
    for (auto& t : pool) t.join();
}

}  // namespace

Result<LocalTinStats> storeLocalTins(io::StoreWriter& w, const TinFeatures& features,
                                     const LocalTinOptions& o, Progress& progress) {
    Diagnostics d;
    if (!w.grid() || !w.hasTable(o.elevation)) {
        d.error("IMPORT_NO_ELEVATION", w.path(), o.elevation,
                "store has no elevation layer \"" + o.elevation +
                    "\" for the TINs (import elevation first)");
        return d;
    }
    d.append(w.createTileTins());
    d.append(w.deleteTileTins(o.elevation, o.source));
    if (d.hasErrors()) return d;
    const io::TileGrid grid = *w.grid();
    const Planner planner(grid, features);
    LocalTinStats stats;
    std::int64_t withData = 0;
    std::map<std::string, std::int64_t> replaced;  // other sources whose TINs this replaces
    for (int level = grid.maxLevel(); level >= 0; --level) {
        const std::set<TileId> ids = planner.crossedTiles(level);
        std::vector<TinJob> jobs(ids.size());  // sized once: prepare() keeps pointers into jobs
        std::size_t k = 0;
        for (const TileId& id : ids) {
            TinJob& job = jobs[k++];
            job.id = id;
            auto posts = w.readScalarTile(o.elevation, id);
            if (!posts) {
                if (posts.diagnostics.has("STORE_TILE_MISSING")) continue;
                return posts.diagnostics;
            }
            job.posts = std::move(*posts.value);
            ++withData;
            planner.prepare(job, o.everyFinestTile && level == grid.maxLevel());
        }
        progress.begin("TINs of level " + std::to_string(level), std::int64_t(jobs.size()));
        buildJobs(jobs, o.threads);
        progress.finish();
        int built = 0;
        for (TinJob& job : jobs) {
            if (job.posts.values.empty()) continue;
            ++stats.tilesChecked;
            if (!job.needed) continue;
            const std::string where = io::tileName(o.elevation, job.id);
            if (job.error.hasErrors()) {
                for (Diagnostic e : job.error.items()) {
                    e.file = w.path();
                    e.where = where;
                    d.add(std::move(e));
                }
                return d;
            }
            if (auto other = w.tileTinSource(o.elevation, job.id)) ++replaced[*other];
            for (std::size_t t = 0; t < job.tiers.size(); ++t) {
                const TinJob::Tier& tier = job.tiers[t];
                const io::TinMesh& m = tier.tin.mesh;
                d.append(w.putTileTin(o.elevation, job.id, int(t), o.source, tier.tolerance,
                                      tier.tin.maxError, m.vertexCount(), m.triangleCount(),
                                      tier.blob));
                if (d.hasErrors()) return d;
                stats.blobBytes += std::int64_t(tier.blob.size());
                if (t == 0) stats.maxError = std::max(stats.maxError, tier.tin.maxError);
            }
            stats.rows += std::int64_t(job.tiers.size());
            ++built;
            ++stats.tiles;
            stats.tinTriangles += std::int64_t(job.tiers[0].tin.mesh.triangleCount());
            stats.gridTriangles += std::int64_t(job.gridTriangles);
            if (stats.finestLevel < 0) stats.finestLevel = level;
            stats.coarsestLevel = level;
        }
        // Coarser tiles have larger errors: once the grid keeps the features at one level it
        // keeps them at every coarser one.
        if (built == 0) break;
    }
    if (withData == 0) {
        d.error("IMPORT_TIN_OUTSIDE", w.path(), o.elevation,
                "the lines cross no tile of the elevation layer that has data (wrong CRS, or lines "
                "outside the store's extent)");
        return d;
    }
    if (stats.tiles == 0)
        d.warning("IMPORT_TIN_NONE", w.path(), o.elevation,
                  "the grid keeps every line within its tiles' error bounds: no TIN was needed");
    for (const auto& [source, tiles] : replaced)
        d.warning("IMPORT_TIN_REPLACED", w.path(), o.elevation,
                  std::to_string(tiles) + " tiles had a TIN from '" + source + "': replaced by '" +
                      o.source + "' (one TIN per tile)");
    return Result<LocalTinStats>(stats, std::move(d));
}

Diagnostics heightsFromElevation(io::StoreWriter& w, const std::string& elevation,
                                 std::vector<std::vector<glm::dvec3>>& lines) {
    Diagnostics d;
    const io::TileGrid& grid = *w.grid();
    const int level = grid.maxLevel();
    const io::TileMatrix& m = grid.levels[std::size_t(level)];
    std::map<TileId, io::RasterTile> cache;  // the finest tiles the lines touch
    auto height = [&](double x, double y) -> double {
        // The post cell holding (x, y), and the tile holding that cell (tiles share a post row).
        const double u = (x - grid.minX) / m.pixelXSize - 0.5,
                     v = (grid.maxY - y) / m.pixelYSize - 0.5;
        if (u < 0 || v < 0) return kNan;
        const int col = std::min(int(u) / m.tileWidth, m.matrixWidth - 1);
        const int row = std::min(int(v) / m.tileHeight, m.matrixHeight - 1);
        const TileId id{level, col, row};
        auto it = cache.find(id);
        if (it == cache.end()) {
            auto t = w.readScalarTile(elevation, id);
            if (!t && !t.diagnostics.has("STORE_TILE_MISSING")) d.append(t.diagnostics);
            it = cache.emplace(id, t ? std::move(*t.value) : io::RasterTile{}).first;
        }
        if (it->second.values.empty()) return kNan;
        return bilinear(it->second, u - double(col) * m.tileWidth, v - double(row) * m.tileHeight);
    };
    std::vector<std::vector<glm::dvec3>> out;
    const double step = std::min(m.pixelXSize, m.pixelYSize);
    for (const auto& line : lines) {
        std::vector<glm::dvec3> part;
        auto flush = [&] {
            if (part.size() >= 2) out.push_back(part);
            part.clear();
        };
        for (std::size_t k = 0; k + 1 < line.size(); ++k) {
            const glm::dvec2 a(line[k]), b(line[k + 1]);
            const int steps = std::max(1, int(std::ceil(glm::length(b - a) / step)));
            for (int s = (k == 0 ? 0 : 1); s <= steps; ++s) {
                const glm::dvec2 p = a + (b - a) * (double(s) / steps);
                const double z = height(p.x, p.y);
                if (!std::isfinite(z)) {
                    flush();
                    continue;
                }
                part.emplace_back(p.x, p.y, z);
            }
            if (d.hasErrors()) return d;
        }
        flush();
    }
    lines = std::move(out);
    return d;
}

}  // namespace kiosk::import
