#pragma once

#include "runtime/io/StoreTypes.h"

#include <filesystem>
#include <vector>

namespace kiosk::test {

/**
 * @brief The finest-level posts of a store's "elevation" layer, in memory: the full-resolution
 * surface that LOD renders are checked against.
 */
class StoreSurface {
public:
    explicit StoreSurface(const std::filesystem::path& store);
    /** @brief Bilinear height at world (X, Y); NaN outside the data or next to nodata. */
    double at(double X, double Y) const;
    /**
     * @brief Heights at world (X, Y) of the two triangulations of the post cell holding it
     * (diagonal NW-SE in `a`, NE-SW in `b`); false outside the data or next to nodata.
     */
    bool triangulated(double X, double Y, double& a, double& b) const;
    const io::TileGrid& grid() const { return mGrid; }

private:
    bool cell(double X, double Y, int& x0, int& y0, double& ax, double& ay) const;
    double z(int x, int y) const {
        return double(mZ[std::size_t(y) * std::size_t(mW) + std::size_t(x)]);
    }

    io::TileGrid mGrid;
    int mW = 0, mH = 0;
    std::vector<float> mZ;
};

}  // namespace kiosk::test
