#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace kiosk::topo::test {

/** @brief A whole raster band in memory: floats with nodata as NaN, or bytes. */
struct FloatRaster {
    int width = 0;
    int height = 0;
    double geoTransform[6] = {0, 1, 0, 0, 0, 1};
    std::vector<float> values;
};

struct ByteRaster {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> values;
};

/** @brief Reads band 1 of `path` as float, nodata -> NaN. Empty optional + message on error. */
std::optional<FloatRaster> readFloat(const std::string& path, std::string& error);
std::optional<ByteRaster> readByte(const std::string& path, std::string& error);

/** @brief Writes a Float32 GeoTIFF with the raster's geotransform (no CRS), NaN as nodata. */
bool writeFloatTiff(const std::string& path, const FloatRaster& r, std::string& error);

/** @brief Path of the gdaldem executable, or empty if it is not installed. */
std::string gdaldemPath();

/** @brief Runs `gdaldem hillshade <args> in out -q` (PAM off). Returns the exit status. */
int runGdaldem(const std::string& args, const std::string& in, const std::string& out);

/** @brief A fresh temporary directory (removed by the caller with removeDir()). */
std::string makeTempDir();
void removeDir(const std::string& dir);

/** @brief $KIOSK_SHARED_DATA/rel (or ../shared/data/rel from the repo root) if it exists. */
std::string sharedData(const std::string& rel);

}  // namespace kiosk::topo::test
