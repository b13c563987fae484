#include "runtime/import/Pyramid.h"

#include "runtime/io/ImageCodec.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <thread>

namespace kiosk::import {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Runs fn(i) for i in [0, n) on `threads` threads (the caller's included).
template <class Fn>
void parallelFor(std::size_t n, int threads, Fn&& fn) {
    const std::size_t t = std::max<std::size_t>(1, std::min<std::size_t>(std::size_t(threads), n));
    if (t <= 1) {
        for (std::size_t i = 0; i < n; ++i) fn(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t i = next++; i < n; i = next++) fn(i);
    };
    std::vector<std::thread> pool;
    for (std::size_t k = 1; k < t; ++k) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
}

GridWindow coarser(const GridWindow& w) {
    return {w.x0 / 2, w.y0 / 2, (w.x1 + 1) / 2, (w.y1 + 1) / 2};
}

struct TileRange {
    int c0, c1, r0, r1;  // inclusive
};

TileRange tilesOf(const GridWindow& w, int t) {
    return {w.x0 / t, (w.x1 - 1) / t, w.y0 / t, (w.y1 - 1) / t};
}

// The post grid of a tile reaches one pixel past the tile; at the data's east/south edge that
// post replicates the last pixel (StoreTypes.h contract).
int borderClamp(int g, bool border, int end) {
    return border && g == end ? end - 1 : g;
}

float categoricalMode(const float* v, int n) {
    float best = kNaN;
    int bestCount = 0;
    for (int i = 0; i < n; ++i) {
        if (std::isnan(v[i])) continue;
        int count = 0;
        for (int j = 0; j < n; ++j) count += v[j] == v[i];
        if (count > bestCount || (count == bestCount && v[i] > best)) {
            best = v[i];
            bestCount = count;
        }
    }
    return best;
}

struct ScalarJob {
    TileId id;
    std::optional<io::EncodedScalarTile> tile;
    Diagnostics diagnostics;
};

struct AxisNode {
    int i0, i1;  // coarse posts
    float w;
    int q0, q1;  // fine pixels
    float wq;
};

std::vector<AxisNode> axisNodes(int t) {
    std::vector<AxisNode> nodes;
    // Half-unit positions v on the finer level's pixel-centre axis (centre of pixel a at a+0.5):
    // finer posts sit at odd v, coarser post lines at v = 2 mod 4; between these both surfaces
    // are bilinear, so the extreme deviation lies on this lattice.
    for (int v = 2; v <= 4 * t + 2; ++v) {
        if (v % 2 == 0 && v % 4 != 2) continue;
        AxisNode n;
        const double p = (v - 2) / 4.0;
        n.i0 = std::min(int(std::floor(p)), t);
        n.i1 = std::min(n.i0 + 1, t);
        n.w = float(p - n.i0);
        const double q = (v - 1) / 2.0;
        n.q0 = int(std::floor(q));
        n.q1 = std::min(n.q0 + 1, 2 * t + 1);
        n.wq = float(q - n.q0);
        nodes.push_back(n);
    }
    return nodes;
}

inline float lerp2(const float* a, int stride, int x0, int x1, float wx, int y0, int y1, float wy) {
    auto at = [&](int x, int y) {
        return a[std::size_t(y) * std::size_t(stride) + std::size_t(x)];
    };
    float top = at(x0, y0), bottom = 0;
    if (wx > 0) top = top * (1 - wx) + at(x1, y0) * wx;
    if (wy > 0) {
        bottom = at(x0, y1);
        if (wx > 0) bottom = bottom * (1 - wx) + at(x1, y1) * wx;
        return top * (1 - wy) + bottom * wy;
    }
    return top;
}

}  // namespace

float surfaceDeviation(const std::vector<float>& posts, const std::vector<float>& fine, int tile) {
    static thread_local std::vector<AxisNode> nodes;
    static thread_local int nodesFor = -1;
    if (nodesFor != tile) {
        nodes = axisNodes(tile);
        nodesFor = tile;
    }
    const int ps = tile + 1, fs = 2 * tile + 2;
    float d = 0;
    for (const AxisNode& ny : nodes) {
        for (const AxisNode& nx : nodes) {
            const float a = lerp2(posts.data(), ps, nx.i0, nx.i1, nx.w, ny.i0, ny.i1, ny.w);
            const float b = lerp2(fine.data(), fs, nx.q0, nx.q1, nx.wq, ny.q0, ny.q1, ny.wq);
            const float e = std::fabs(a - b);
            if (e > d) d = e;  // NaN compares false: nodata is skipped
        }
    }
    return d;
}

std::int64_t estimateTiles(const io::TileGrid& grid, const GridWindow& window) {
    std::int64_t n = 0;
    GridWindow w = window;
    const int t = grid.levels.back().tileWidth;
    for (int l = grid.maxLevel(); l >= 0 && !w.empty(); --l) {
        const TileRange r = tilesOf(w, t);
        n += std::int64_t(r.c1 - r.c0 + 1) * std::int64_t(r.r1 - r.r0 + 1);
        w = coarser(w);
    }
    return n;
}

/** A tile was written: count it, report progress, honour the failure-injection test hook. */
static bool countTile(PyramidResult& res, const PyramidOptions& opt, Diagnostics& diag) {
    ++res.tiles;
    if (opt.progress) opt.progress->advance();
    if (opt.failAfterTiles >= 0 && res.tiles >= opt.failAfterTiles) {
        diag.error("IMPORT_INJECTED_FAILURE", opt.sourceName, opt.table,
                   "failure injected after " + std::to_string(res.tiles) + " tiles");
        return false;
    }
    return true;
}

Result<PyramidResult> buildScalarPyramid(io::StoreWriter& writer, const io::TileGrid& grid,
                                         const GridWindow& window, const ScalarRowSource& source,
                                         const PyramidOptions& opt) {
    Diagnostics diag;
    const int t = grid.levels.back().tileWidth;
    const int maxLevel = grid.maxLevel();
    const std::size_t ps = std::size_t(t + 1);
    PyramidResult res;
    res.minValue = std::numeric_limits<double>::infinity();
    res.maxValue = -res.minValue;
    bool clampWarned = false;

    auto writeJobs = [&](std::vector<ScalarJob>& jobs, bool finest) -> bool {
        for (ScalarJob& j : jobs) {
            if (j.diagnostics.hasErrors()) {
                diag.append(j.diagnostics);
                return false;
            }
            if (!j.tile) continue;
            diag.append(writer.putScalarTile(opt.table, j.id, *j.tile));
            if (diag.hasErrors()) return false;
            if (finest) {
                res.minValue = std::min(res.minValue, double(j.tile->stats.minValue));
                res.maxValue = std::max(res.maxValue, double(j.tile->stats.maxValue));
            }
            if (j.tile->clamped && !clampWarned) {
                clampWarned = true;
                res.clamped = true;
                diag.warning("IMPORT_RANGE_CLAMPED", opt.sourceName, io::tileName(opt.table, j.id),
                             "value range of a tile exceeds 16 bits at the chosen precision; "
                             "values clamped");
            }
            if (!countTile(res, opt, diag)) return false;
        }
        return true;
    };

    // Finest level, straight from the source, one strip of T + 1 rows per tile row.
    {
        const TileRange tr = tilesOf(window, t);
        const int w = window.width();
        std::vector<float> strip;
        for (int r = tr.r0; r <= tr.r1; ++r) {
            const int gy0 = std::max(window.y0, r * t);
            const int gy1 = std::min(window.y1, r * t + t + 1);
            strip.assign(std::size_t(gy1 - gy0) * std::size_t(w), kNaN);
            diag.append(source(gy0 - window.y0, gy1 - gy0, strip.data()));
            if (diag.hasErrors()) return diag;
            std::vector<ScalarJob> jobs(std::size_t(tr.c1 - tr.c0 + 1));
            parallelFor(jobs.size(), opt.threads, [&](std::size_t k) {
                const int c = tr.c0 + int(k);
                ScalarJob& job = jobs[k];
                job.id = TileId{maxLevel, c, r};
                std::vector<float> posts(ps * ps, kNaN);
                bool any = false;
                for (int y = 0; y <= t; ++y) {
                    const int gy = borderClamp(r * t + y, y == t, window.y1);
                    if (gy < window.y0 || gy >= window.y1) continue;
                    const float* row = &strip[std::size_t(gy - gy0) * std::size_t(w)];
                    for (int x = 0; x <= t; ++x) {
                        const int gx = borderClamp(c * t + x, x == t, window.x1);
                        if (gx < window.x0 || gx >= window.x1) continue;
                        const float v = row[gx - window.x0];
                        posts[std::size_t(y) * ps + std::size_t(x)] = v;
                        any = any || (x < t && y < t && !std::isnan(v));
                    }
                }
                if (!any) return;
                io::quantizePosts(posts, opt.scale);
                auto enc = io::encodeScalarTile(posts, t, t, opt.scale, opt.pngLevel);
                if (!enc) {
                    job.diagnostics = enc.diagnostics;
                    return;
                }
                enc->stats.geometricError = 0;
                job.tile = std::move(*enc);
            });
            if (!writeJobs(jobs, true)) return diag;
        }
    }
    if (res.tiles == 0) {
        diag.error("IMPORT_ALL_NODATA", opt.sourceName, opt.table,
                   "source holds no valid value (all nodata) inside the store extent");
        return diag;
    }

    // Coarser levels from the level below, read back from the store.
    GridWindow childWin = window;
    for (int level = maxLevel - 1; level >= 0; --level) {
        const GridWindow win = coarser(childWin);
        const TileRange tr = tilesOf(win, t);
        const TileRange cr = tilesOf(childWin, t);
        std::map<std::pair<int, int>, std::shared_ptr<const io::RasterTile>> cache;  // (row, col)
        auto child = [&](int col, int row) -> const io::RasterTile* {
            auto it = cache.find({row, col});
            return it == cache.end() ? nullptr : it->second.get();
        };
        for (int r = tr.r0; r <= tr.r1; ++r) {
            for (auto it = cache.begin(); it != cache.end();)
                it = it->first.first < 2 * r ? cache.erase(it) : std::next(it);
            for (int row = 2 * r; row <= std::min(2 * r + 2, cr.r1); ++row) {
                for (int col = std::max(2 * tr.c0, cr.c0); col <= std::min(2 * tr.c1 + 2, cr.c1);
                     ++col) {
                    if (cache.count({row, col})) continue;
                    auto tile = writer.readScalarTile(opt.table, TileId{level + 1, col, row});
                    if (tile)
                        cache[{row, col}] = std::make_shared<io::RasterTile>(std::move(*tile));
                    else if (tile.diagnostics.has("STORE_TILE_MISSING"))
                        cache[{row, col}] = nullptr;
                    else {
                        diag.append(tile.diagnostics);
                        return diag;
                    }
                }
            }
            std::vector<ScalarJob> jobs(std::size_t(tr.c1 - tr.c0 + 1));
            parallelFor(jobs.size(), opt.threads, [&](std::size_t k) {
                const int c = tr.c0 + int(k);
                ScalarJob& job = jobs[k];
                job.id = TileId{level, c, r};
                const int fs = 2 * t + 2;
                std::vector<float> fine(std::size_t(fs) * std::size_t(fs), kNaN);
                const io::RasterTile* kids[3][3];
                for (int j = 0; j < 3; ++j)
                    for (int i = 0; i < 3; ++i) kids[j][i] = child(2 * c + i, 2 * r + j);
                for (int b = 0; b < fs; ++b) {
                    int py = 2 * r * t + b;
                    if (py == childWin.y1) py = childWin.y1 - 1;
                    if (py < childWin.y0 || py >= childWin.y1) continue;
                    for (int a = 0; a < fs; ++a) {
                        int px = 2 * c * t + a;
                        if (px == childWin.x1) px = childWin.x1 - 1;
                        if (px < childWin.x0 || px >= childWin.x1) continue;
                        const io::RasterTile* ct = kids[py / t - 2 * r][px / t - 2 * c];
                        if (!ct) continue;
                        fine[std::size_t(b) * std::size_t(fs) + std::size_t(a)] =
                            ct->values[std::size_t(py % t) * ps + std::size_t(px % t)];
                    }
                }
                std::vector<float> posts(ps * ps, kNaN);
                bool any = false;
                for (int y = 0; y <= t; ++y) {
                    const int gy = borderClamp(r * t + y, y == t, win.y1);
                    if (gy < win.y0 || gy >= win.y1) continue;
                    const int b = 2 * (gy - r * t);
                    for (int x = 0; x <= t; ++x) {
                        const int gx = borderClamp(c * t + x, x == t, win.x1);
                        if (gx < win.x0 || gx >= win.x1) continue;
                        const int a = 2 * (gx - c * t);
                        const float q[4] = {
                            fine[std::size_t(b) * std::size_t(fs) + std::size_t(a)],
                            fine[std::size_t(b) * std::size_t(fs) + std::size_t(a + 1)],
                            fine[std::size_t(b + 1) * std::size_t(fs) + std::size_t(a)],
                            fine[std::size_t(b + 1) * std::size_t(fs) + std::size_t(a + 1)]};
                        float v = kNaN;
                        if (opt.categorical) {
                            v = categoricalMode(q, 4);
                        } else {
                            float sum = 0;
                            int n = 0;
                            for (float s : q)
                                if (!std::isnan(s)) sum += s, ++n;
                            if (n) v = sum / float(n);
                        }
                        posts[std::size_t(y) * ps + std::size_t(x)] = v;
                        any = any || (x < t && y < t && !std::isnan(v));
                    }
                }
                if (!any) return;
                io::quantizePosts(posts, opt.scale);
                float childError = 0;
                for (int j = 0; j <= 2; ++j)
                    for (int i = 0; i <= 2; ++i)
                        if (const io::RasterTile* ct = child(2 * c + i, 2 * r + j))
                            childError = std::max(childError, ct->stats.geometricError);
                auto enc = io::encodeScalarTile(posts, t, t, opt.scale, opt.pngLevel);
                if (!enc) {
                    job.diagnostics = enc.diagnostics;
                    return;
                }
                // Rounding of the float32 sums may add an ulp; pad so the bound stays a bound.
                const float dev = surfaceDeviation(posts, fine, t);
                enc->stats.geometricError =
                    opt.categorical ? 0.f : (dev + childError) * (1.f + 1e-6f) + 1e-6f;
                job.tile = std::move(*enc);
            });
            if (!writeJobs(jobs, false)) return diag;
        }
        childWin = win;
    }
    return Result<PyramidResult>(res, std::move(diag));
}

Result<PyramidResult> buildImageryPyramid(io::StoreWriter& writer, const io::TileGrid& grid,
                                          const GridWindow& window, const RgbaRowSource& source,
                                          const PyramidOptions& opt) {
    Diagnostics diag;
    const int t = grid.levels.back().tileWidth;
    const int maxLevel = grid.maxLevel();
    const std::size_t tt = std::size_t(t) * std::size_t(t);
    PyramidResult res;

    struct ImageJob {
        TileId id;
        std::vector<std::uint8_t> blob;
        Diagnostics diagnostics;
    };
    auto encodeTile = [&](const std::vector<std::uint8_t>& rgba, ImageJob& job) {
        bool opaque = true, empty = true;
        for (std::size_t i = 0; i < tt; ++i) {
            opaque = opaque && rgba[i * 4 + 3] == 255;
            empty = empty && rgba[i * 4 + 3] == 0;
        }
        if (empty) return;
        Result<std::vector<std::uint8_t>> enc;
        if (opaque) {
            std::vector<std::uint8_t> rgb(tt * 3);
            for (std::size_t i = 0; i < tt; ++i)
                for (int k = 0; k < 3; ++k)
                    rgb[i * 3 + std::size_t(k)] = rgba[i * 4 + std::size_t(k)];
            enc = opt.jpeg ? io::encodeJpeg(rgb.data(), t, t, 90)
                           : io::encodePng8(rgb.data(), t, t, 3, opt.pngLevel);
        } else {
            enc = io::encodePng8(rgba.data(), t, t, 4, opt.pngLevel);
        }
        if (!enc)
            job.diagnostics = enc.diagnostics;
        else
            job.blob = std::move(*enc);
    };
    auto writeJobs = [&](std::vector<ImageJob>& jobs) -> bool {
        for (ImageJob& j : jobs) {
            if (j.diagnostics.hasErrors()) {
                diag.append(j.diagnostics);
                return false;
            }
            if (j.blob.empty()) continue;
            diag.append(writer.putImageTile(opt.table, j.id, j.blob));
            if (diag.hasErrors()) return false;
            if (!countTile(res, opt, diag)) return false;
        }
        return true;
    };

    {
        const TileRange tr = tilesOf(window, t);
        const int w = window.width();
        std::vector<std::uint8_t> strip;
        for (int r = tr.r0; r <= tr.r1; ++r) {
            const int gy0 = std::max(window.y0, r * t);
            const int gy1 = std::min(window.y1, r * t + t);
            strip.assign(std::size_t(gy1 - gy0) * std::size_t(w) * 4, 0);
            diag.append(source(gy0 - window.y0, gy1 - gy0, strip.data()));
            if (diag.hasErrors()) return diag;
            std::vector<ImageJob> jobs(std::size_t(tr.c1 - tr.c0 + 1));
            parallelFor(jobs.size(), opt.threads, [&](std::size_t k) {
                const int c = tr.c0 + int(k);
                jobs[k].id = TileId{maxLevel, c, r};
                std::vector<std::uint8_t> rgba(tt * 4, 0);
                for (int gy = gy0; gy < gy1; ++gy) {
                    const int y = gy - r * t;
                    for (int x = 0; x < t; ++x) {
                        const int gx = c * t + x;
                        if (gx < window.x0 || gx >= window.x1) continue;
                        const std::uint8_t* s = &strip[(std::size_t(gy - gy0) * std::size_t(w) +
                                                        std::size_t(gx - window.x0)) *
                                                       4];
                        std::copy(s, s + 4,
                                  &rgba[(std::size_t(y) * std::size_t(t) + std::size_t(x)) * 4]);
                    }
                }
                encodeTile(rgba, jobs[k]);
            });
            if (!writeJobs(jobs)) return diag;
        }
    }
    if (res.tiles == 0) {
        diag.error("IMPORT_ALL_NODATA", opt.sourceName, opt.table,
                   "imagery is fully transparent inside the store extent");
        return diag;
    }
    GridWindow childWin = window;
    for (int level = maxLevel - 1; level >= 0; --level) {
        const GridWindow win = coarser(childWin);
        const TileRange tr = tilesOf(win, t);
        for (int r = tr.r0; r <= tr.r1; ++r) {
            std::map<std::pair<int, int>, std::shared_ptr<io::ImageTile>> kids;
            for (int row = 2 * r; row <= 2 * r + 1; ++row)
                for (int col = 2 * tr.c0; col <= 2 * tr.c1 + 1; ++col) {
                    auto tile = writer.readImageTile(opt.table, TileId{level + 1, col, row});
                    if (tile)
                        kids[{row, col}] = std::make_shared<io::ImageTile>(std::move(*tile));
                    else if (!tile.diagnostics.has("STORE_TILE_MISSING")) {
                        diag.append(tile.diagnostics);
                        return diag;
                    }
                }
            std::vector<ImageJob> jobs(std::size_t(tr.c1 - tr.c0 + 1));
            parallelFor(jobs.size(), opt.threads, [&](std::size_t k) {
                const int c = tr.c0 + int(k);
                jobs[k].id = TileId{level, c, r};
                std::vector<std::uint8_t> rgba(tt * 4, 0);
                for (int y = 0; y < t; ++y)
                    for (int x = 0; x < t; ++x) {
                        unsigned sum[3] = {0, 0, 0}, alpha = 0;
                        for (int j = 0; j < 2; ++j)
                            for (int i = 0; i < 2; ++i) {
                                const int px = 2 * (c * t + x) + i, py = 2 * (r * t + y) + j;
                                auto it = kids.find({py / t, px / t});
                                if (it == kids.end()) continue;
                                const std::uint8_t* s =
                                    &it->second->rgba[(std::size_t(py % t) * std::size_t(t) +
                                                       std::size_t(px % t)) *
                                                      4];
                                for (int ch = 0; ch < 3; ++ch) sum[ch] += unsigned(s[ch]) * s[3];
                                alpha += s[3];
                            }
                        if (alpha == 0) continue;
                        std::uint8_t* o =
                            &rgba[(std::size_t(y) * std::size_t(t) + std::size_t(x)) * 4];
                        for (int ch = 0; ch < 3; ++ch)
                            o[ch] = std::uint8_t((sum[ch] + alpha / 2) / alpha);
                        o[3] = std::uint8_t((alpha + 2) / 4);
                    }
                encodeTile(rgba, jobs[k]);
            });
            if (!writeJobs(jobs)) return diag;
        }
        childWin = win;
    }
    return Result<PyramidResult>(res, std::move(diag));
}

}  // namespace kiosk::import
