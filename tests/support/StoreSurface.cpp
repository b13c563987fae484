#include "tests/support/StoreSurface.h"

#include "runtime/io/StoreReader.h"

#include <cmath>

namespace kiosk::test {

StoreSurface::StoreSurface(const std::filesystem::path& store) {
    auto r = io::StoreReader::open(store);
    if (!r) return;
    mGrid = (*r)->info().grid;
    const io::TileMatrix& m = mGrid.levels.back();
    mW = m.matrixWidth * m.tileWidth;
    mH = m.matrixHeight * m.tileHeight;
    mZ.assign(std::size_t(mW) * std::size_t(mH), std::nanf(""));
    for (int row = 0; row < m.matrixHeight; ++row)
        for (int col = 0; col < m.matrixWidth; ++col) {
            auto t = (*r)->readElevation("elevation", {mGrid.maxLevel(), col, row});
            if (!t) continue;
            for (int y = 0; y < m.tileHeight; ++y)
                for (int x = 0; x < m.tileWidth; ++x)
                    mZ[std::size_t(row * m.tileHeight + y) * std::size_t(mW) +
                       std::size_t(col * m.tileWidth + x)] = t->at(x, y);
        }
}

bool StoreSurface::cell(double X, double Y, int& x0, int& y0, double& ax, double& ay) const {
    if (mGrid.levels.empty()) return false;
    const io::TileMatrix& m = mGrid.levels.back();
    // Post (i, j) sits at the centre of pixel (i, j).
    const double fx = (X - mGrid.minX) / m.pixelXSize - 0.5,
                 fy = (mGrid.maxY - Y) / m.pixelYSize - 0.5;
    x0 = int(std::floor(fx));
    y0 = int(std::floor(fy));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= mW || y0 + 1 >= mH) return false;
    ax = fx - x0;
    ay = fy - y0;
    return true;
}

double StoreSurface::at(double X, double Y) const {
    int x0, y0;
    double ax, ay;
    if (!cell(X, Y, x0, y0, ax, ay)) return std::nan("");
    return (1 - ay) * ((1 - ax) * z(x0, y0) + ax * z(x0 + 1, y0)) +
           ay * ((1 - ax) * z(x0, y0 + 1) + ax * z(x0 + 1, y0 + 1));
}

bool StoreSurface::triangulated(double X, double Y, double& a, double& b) const {
    int x0, y0;
    double ax, ay;
    if (!cell(X, Y, x0, y0, ax, ay)) return false;
    const double z00 = z(x0, y0), z10 = z(x0 + 1, y0), z01 = z(x0, y0 + 1), z11 = z(x0 + 1, y0 + 1);
    a = ax >= ay ? z00 + ax * (z10 - z00) + ay * (z11 - z10)
                 : z00 + ay * (z01 - z00) + ax * (z11 - z01);
    b = ax + ay <= 1 ? z00 + ax * (z10 - z00) + ay * (z01 - z00)
                     : z11 + (1 - ax) * (z01 - z11) + (1 - ay) * (z10 - z11);
    return !std::isnan(a) && !std::isnan(b);
}

}  // namespace kiosk::test
