#include "runtime/import/Topographic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "runtime/core/Progress.h"
#include "runtime/import/Pyramid.h"
#include "runtime/import/TempStore.h"
#include "runtime/topo/NormalMap.h"
#include "runtime/topo/Shadow.h"

namespace kiosk::import {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

/**
 * Finest-level elevation rows on demand, one tile row at a time: only the tile rows a strip and
 * its apron touch are held, so memory is a few tile rows of the DEM's width.
 */
class ElevationRows {
public:
    ElevationRows(io::StoreWriter& w, std::string table, const io::TileGrid& grid)
        : mWriter(w), mTable(std::move(table)), mLevel(grid.maxLevel()),
          mMatrix(grid.levels[std::size_t(grid.maxLevel())]) {}

    int width() const { return mMatrix.matrixWidth * mMatrix.tileWidth; }
    int height() const { return mMatrix.matrixHeight * mMatrix.tileHeight; }

    /** Copy rows [y0, y1) into `out` (width() floats per row); missing tiles are NaN. */
    Diagnostics rows(int y0, int y1, float* out) {
        Diagnostics d;
        const int th = mMatrix.tileHeight;
        // Drop tile rows above the request: strips only move south.
        for (auto it = mTileRows.begin(); it != mTileRows.end();)
            it = it->first < y0 / th ? mTileRows.erase(it) : std::next(it);
        for (int y = y0; y < y1; ++y) {
            const int tr = y / th;
            auto it = mTileRows.find(tr);
            if (it == mTileRows.end()) {
                it = mTileRows.emplace(tr, std::vector<float>()).first;
                d.append(load(tr, it->second));
                if (d.hasErrors()) return d;
            }
            const float* src = it->second.data() + std::size_t(y % th) * std::size_t(width());
            std::copy(src, src + width(), out + std::size_t(y - y0) * std::size_t(width()));
        }
        return d;
    }

private:
    Diagnostics load(int tileRow, std::vector<float>& buf) {
        Diagnostics d;
        const int tw = mMatrix.tileWidth, th = mMatrix.tileHeight;
        buf.assign(std::size_t(width()) * std::size_t(th), kNan);
        for (int col = 0; col < mMatrix.matrixWidth; ++col) {
            auto tile = mWriter.readScalarTile(mTable, {mLevel, col, tileRow});
            if (!tile) {
                if (tile.diagnostics.has("STORE_TILE_MISSING")) continue;  // outside the data
                d.append(tile.diagnostics);
                return d;
            }
            for (int y = 0; y < th && y < tile->postsY; ++y)
                for (int x = 0; x < tw && x < tile->postsX; ++x)
                    buf[std::size_t(y) * std::size_t(width()) + std::size_t(col * tw + x)] = tile->at(x, y);
        }
        return d;
    }

    io::StoreWriter& mWriter;
    std::string mTable;
    int mLevel;
    io::TileMatrix mMatrix;
    std::map<int, std::vector<float>> mTileRows;
};

}  // namespace

Diagnostics importTopographic(const TopographicOptions& o) {
    return withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        Diagnostics d;
        if (!w.grid() || !w.hasTable(o.elevation)) {
            d.error("IMPORT_NO_ELEVATION", o.store.string(), o.elevation,
                    "store has no elevation layer \"" + o.elevation +
                        "\" to shade (import elevation first)");
            return d;
        }
        if (!io::StoreWriter::validTableName(o.name)) {
            d.error("IMPORT_USAGE", o.store.string(), "--name", "'" + o.name + "' is not a valid layer name");
            return d;
        }
        const io::TileGrid grid = *w.grid();
        const io::TileMatrix& fine = grid.levels[std::size_t(grid.maxLevel())];
        ElevationRows source(w, o.elevation, grid);
        int apron = 1;
        if (o.shadows && !o.normals) {
            auto root = w.readScalarTile(o.elevation, {0, 0, 0});
            const double relief = root ? double(root->stats.maxValue - root->stats.minValue) : 9000.0;
            apron = std::max(1, topo::requiredShadowApron(relief, o.light, fine.pixelXSize, fine.pixelYSize));
        }
        const std::string description =
            o.normals ? "normal map of " + o.elevation + " (rgb8: east, north, up; a: valid)"
                      : "hillshade of " + o.elevation + " (azimuth " +
                            std::to_string(int(o.light.azimuthDeg)) + ", altitude " +
                            std::to_string(int(o.light.altitudeDeg)) + ")";
        d.append(w.createImageryLayer(o.name, description));
        if (d.hasErrors()) return d;
        const GridWindow window{0, 0, source.width(), source.height()};
        const int W = window.width();
        std::vector<float> dem;
        std::vector<std::uint8_t> shade;
        topo::HillshadeParams light = o.light;
        light.computeEdges = true;  // shade up to the data's edge; nodata stays transparent
        auto rows = [&](int row0, int n, std::uint8_t* out) -> Diagnostics {
            const int top = std::max(0, row0 - apron), bottom = std::min(window.height(), row0 + n + apron);
            dem.resize(std::size_t(W) * std::size_t(bottom - top));
            Diagnostics rd = source.rows(top, bottom, dem.data());
            if (rd.hasErrors()) return rd;
            topo::RasterView v;
            v.data = dem.data() + std::size_t(row0 - top) * std::size_t(W);
            v.width = W;
            v.height = n;
            v.stride = W;
            v.apronTop = row0 - top;
            v.apronBottom = bottom - (row0 + n);
            v.pixelSizeX = fine.pixelXSize;
            v.pixelSizeY = fine.pixelYSize;
            if (o.normals) {
                topo::NormalMapParams np;
                np.zFactor = light.zFactor;
                np.scale = light.scale;
                np.algorithm = light.algorithm;
                np.encoding = topo::NormalEncoding::Rgb8;
                shade.assign(std::size_t(W) * std::size_t(n) * 3, 0);
                rd = topo::normalMap(v, np, shade.data(), std::ptrdiff_t(W) * 3);
                if (rd.hasErrors()) return rd;
                for (std::size_t i = 0; i < std::size_t(W) * std::size_t(n); ++i) {
                    // (0, 0, 0) is the encoding's nodata: transparent, so no rim of a false
                    // horizontal normal along the data's edge (a valid blue byte is >= 128).
                    const std::uint8_t* t = &shade[i * 3];
                    out[i * 4 + 0] = t[0];
                    out[i * 4 + 1] = t[1];
                    out[i * 4 + 2] = t[2];
                    out[i * 4 + 3] = t[2] ? 255 : 0;
                }
                return rd;
            }
            shade.assign(std::size_t(W) * std::size_t(n), 0);
            rd = o.shadows ? topo::shadedRelief(v, light, topo::ShadowParams{o.shadowDarkening},
                                                shade.data(), W)
                           : topo::hillshade(v, light, shade.data(), W);
            if (rd.hasErrors()) return rd;
            for (std::size_t i = 0; i < shade.size(); ++i) {
                // Shade 0 is the topo library's nodata: transparent, never a black rim.
                out[i * 4 + 0] = out[i * 4 + 1] = out[i * 4 + 2] = shade[i];
                out[i * 4 + 3] = shade[i] ? 255 : 0;
            }
            return rd;
        };
        Progress progress(o.quiet);
        PyramidOptions opt;
        opt.table = o.name;
        opt.threads = o.threads;
        opt.progress = &progress;
        opt.sourceName = o.store.string();
        progress.begin(o.name, estimateTiles(grid, window));
        auto r = buildImageryPyramid(w, grid, window, rows, opt);
        progress.finish();
        if (!r) return r.diagnostics;
        // Shade exists where the elevation does: its extent, not the whole tile matrix.
        const auto e = w.layerDataExtent(o.elevation);
        d.append(e ? w.finishLayer(o.name, 0, 255, (*e)[0], (*e)[1], (*e)[2], (*e)[3])
                   : w.finishLayer(o.name, 0, 255, grid.minX, grid.minY,
                                   grid.minX + W * fine.pixelXSize, grid.maxY));
        return d;
    });
}

}  // namespace kiosk::import
