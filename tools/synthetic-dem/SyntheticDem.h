#pragma once
// Large synthetic DEMs for the out-of-core and import benchmarks (W04 works on 16k x 16k grids;
// no redistributable DEM of that size is bundled). Written strip by strip: memory is one 256-row
// strip plus GDAL's block cache (5 % of RAM by default; make-synthetic-dem caps it at 64 MiB).
#include <filesystem>
#include <string>

namespace kiosk::tools {

struct SyntheticDemOptions {
    int size = 4096;         ///< posts per side
    double post = 10.0;      ///< metres between posts
    double west = 500000.0;  ///< UTM 10N (EPSG:32610) origin of the north-west corner
    double north = 5300000.0;
};

/** @brief Write a tiled Float32 GeoTIFF of fractal-like ridges and valleys (about 0-4600 m, a
 * little per-post noise, nodata -9999 declared but unused). Returns an empty string or the error.
 */
std::string writeSyntheticDem(const std::filesystem::path& out, const SyntheticDemOptions& o);

}  // namespace kiosk::tools
