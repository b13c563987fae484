#pragma once

#include "runtime/core/Result.h"
#include "runtime/import/GeoTarget.h"

#include <gdal.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

// Curvilinear sources: rasters whose pixels are located by 2-D longitude/latitude arrays (CF
// `coordinates = "lat lon"` with 2-D lat/lon variables, as radar and model products have), which
// GDAL exposes as "GEOLOCATION" metadata. They are warped to the store's CRS through GDAL's
// geolocation-array transformer; there is no geotransform to place them directly.
namespace kiosk::import {

/** @brief What the importer needs to know of a source's geolocation arrays. */
struct Geolocation {
    StoreCrs crs;             ///< the arrays' CRS (WGS 84 for CF lat/lon)
    LonLatExtent extent;      ///< minimum/maximum of the arrays (lon/lat for a geographic CRS)
    std::int64_t pixels = 0;  ///< size of one array
    /// GDAL keeps the arrays and its backmap in temporary GeoTIFFs (under $TMPDIR) behind a
    /// fixed tile cache instead of in RAM: chosen when the arrays would take more than a quarter
    /// of the import budget, or GDAL's own 16-megapixel switch.
    bool onDisk = false;
    std::int64_t bytes = 0;  ///< RAM of GDAL's geolocation transformer (pre-flight estimate)
};

/**
 * @brief The geolocation of a source without a geotransform; nullopt when it has none (or has a
 * geotransform). IMPORT_GEOLOCATION naming `sourceName` when the arrays cannot be read or are
 * not longitude/latitude where their CRS says so.
 */
Result<std::optional<Geolocation>> geolocationOf(GDALDatasetH ds, std::int64_t budget,
                                                 const std::string& sourceName);

/** @brief gdalwarp transformer options (`-to`) for warping a source with this geolocation. */
std::vector<std::string> geolocationWarpArgs(const Geolocation& g);

/** @brief The same as NAME=VALUE transformer options (GDALCreateGenImgProjTransformer2). */
std::vector<std::string> geolocationTransformerOptions(const Geolocation& g);

}  // namespace kiosk::import
