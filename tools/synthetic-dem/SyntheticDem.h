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
    /** Horizontal scale of the relief in metres (the coarsest ridges repeat about every third of
     * it): fixed, so a 16k grid looks like a 4k one (4096 x 10 m) extended, not stretched, and
     * the two fly with the same roughness. */
    double featureMetres = 40960.0;
    /** Per-post random noise, uniform in [0, noiseMetres): a measured DEM's noise, not relief.
     * 5 m at 10 m posts (the first benchmark runs) made every fine tile mesh nearly full
     * density: 2.3 M triangles in a 960x540 view and 2.1 GB RSS in llvmpipe at 1080p. */
    double noiseMetres = 0.5;
};

/** @brief Write a tiled Float32 GeoTIFF of fractal-like ridges and valleys (about 0-4600 m, a
 * little per-post noise, nodata -9999 declared but unused). Returns an empty string or the error.
 */
std::string writeSyntheticDem(const std::filesystem::path& out, const SyntheticDemOptions& o);

}  // namespace kiosk::tools
