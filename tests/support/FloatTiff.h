#pragma once
// Synthetic GeoTIFFs from a function of (column, row): the DEMs, drapes and frames the GL tests
// import.
#include <functional>
#include <string>

namespace kiosk::test {

/**
 * @brief Write `size` x `size` posts, north-west corner (west, north), `post` metres apart;
 * `nodata` is declared when given. Returns "" or what went wrong.
 */
std::string writeFloatTiff(const std::string& path, int size, double west, double north,
                           double post, const std::function<float(int, int)>& value,
                           const double* nodata = nullptr);

/** @brief The georeference and layout of writeRasterTiff's output. */
struct RasterSpec {
    int width = 0, height = 0;
    double geoTransform[6] = {0, 1, 0, 0, 0, -1};  ///< GDAL order: west, px, 0, north, 0, -py
    int epsg = 32610;
    int bands = 1;        ///< 1: Float32 (elevation, frames); 3: Byte RGB (a drape)
    bool nodata = false;  ///< declare NaN as nodata (band 1 only, Float32)
};

/** @brief Write `value(band, column, row)` (band from 0) as `spec` says. "" or what went wrong. */
std::string writeRasterTiff(const std::string& path, const RasterSpec& spec,
                            const std::function<double(int, int, int)>& value);

}  // namespace kiosk::test
