#pragma once
// A single-band Float32 GeoTIFF in UTM zone 10N (EPSG:32610) from a function of (column, row):
// the synthetic DEMs the GL tests import.
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

}  // namespace kiosk::test
