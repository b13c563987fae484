#include "config/StoreGrids.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace kiosk::config {
namespace {

bool near(double a, double b, double tolerance) {
    return std::abs(a - b) <= tolerance;
}

std::string number(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

}  // namespace

bool sameCrs(const io::TileGrid& a, const io::TileGrid& b) {
    if (a.srsId != 0 && b.srsId != 0) return a.srsId == b.srsId;
    return a.crsWkt == b.crsWkt;
}

std::string crsText(const io::TileGrid& g) {
    std::string name = g.crsName.empty() ? std::string("unnamed CRS") : g.crsName;
    if (g.srsId > 0) name += " (srs_id " + std::to_string(g.srsId) + ")";  // as `info` says
    return name;
}

std::string tileGridDifference(const io::TileGrid& a, const io::TileGrid& b) {
    if (a.levels.empty() || b.levels.empty()) return "a store has no tile matrix";
    // A hundredth of the finest common pixel: float noise in the stored bounds is far below.
    const std::size_t common = std::min(a.levels.size(), b.levels.size());
    const double tol =
        0.01 * std::min(a.levels[common - 1].pixelXSize, b.levels[common - 1].pixelXSize);
    if (!near(a.minX, b.minX, tol) || !near(a.maxY, b.maxY, tol))
        return "tile grid origin (" + number(b.minX) + ", " + number(b.maxY) + ") differs from (" +
               number(a.minX) + ", " + number(a.maxY) + ")";
    for (std::size_t l = 0; l < common; ++l) {
        const io::TileMatrix &ma = a.levels[l], &mb = b.levels[l];
        if (ma.tileWidth != mb.tileWidth || ma.tileHeight != mb.tileHeight)
            return "tile size " + std::to_string(mb.tileWidth) + "x" +
                   std::to_string(mb.tileHeight) + " differs from " + std::to_string(ma.tileWidth) +
                   "x" + std::to_string(ma.tileHeight);
        if (!near(ma.pixelXSize, mb.pixelXSize, 1e-6 * ma.pixelXSize) ||
            !near(ma.pixelYSize, mb.pixelYSize, 1e-6 * ma.pixelYSize))
            return "level " + std::to_string(l) + " pixel size " + number(mb.pixelXSize) +
                   " differs from " + number(ma.pixelXSize);
    }
    return {};
}

}  // namespace kiosk::config
