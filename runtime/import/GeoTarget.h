#pragma once

#include "runtime/core/Result.h"
#include "runtime/import/GdalRaster.h"

#include <gdal.h>

#include <cstdint>
#include <optional>
#include <string>

// Geographic (longitude/latitude) sources: recognising CF lon/lat axes, normalising 0..360
// longitudes, choosing the metric target CRS, and the importer's pre-flight memory budget.
// docs/store-format.md "Geographic inputs" is the user-facing statement of these rules.
namespace kiosk::import {

/**
 * @brief True when a CRS-less dataset's axes are CF longitude/latitude coordinates
 * (units degrees_east/degrees_north and their CF spellings, or standard_name longitude/latitude),
 * as the netCDF driver reports them in `VAR#units` / `VAR#standard_name` metadata.
 */
bool hasCfLonLatAxes(GDALDatasetH ds);

/** @brief WGS 84 geographic (EPSG:4326), the CF default for bare lon/lat axes. */
StoreCrs wgs84();

/** @brief Longitude/latitude extent of a geographic dataset (west may exceed 180). */
struct LonLatExtent {
    double west = 0, east = 0, south = 0, north = 0;
    double lonSpan() const { return east - west; }
    double latSpan() const { return north - south; }
    /** @brief Centre longitude normalised to [-180, 180). */
    double centreLon() const;
};
LonLatExtent lonLatExtent(GDALDatasetH ds);

/** @brief Columns past the globe's that a whole-globe grid may repeat (a wrap column at the end,
 *  or one at each side). */
constexpr int kMaxWrapColumns = 2;

/**
 * @brief The number of columns that make one turn of the globe when the geotransform `gt` of a
 * grid `width` columns wide (in degrees) is a whole globe: 360 / step a whole number n (within
 * 1 % of a column), width n to n + kMaxWrapColumns, and the first column within -360..360;
 * 0 otherwise.
 */
int globeColumns(const double gt[6], int width);

/**
 * @brief Longitudes in -180..180 where possible: a whole-globe grid (globeColumns) from any start
 * meridian keeps its first turn of columns, dropping those past 360 degrees (they repeat
 * meridians it has), and is rolled (a VRT of its two parts) to start near -180; a grid wholly
 * east of 180 (0..360 style) is shifted by -360; another grid spanning the globe on 0..360 is
 * rolled to -180..180; a regional grid crossing the dateline keeps continuous longitudes
 * (170..190), which the target CRS below handles. Returns `ds` itself when nothing changes; new
 * datasets go to `chain`.
 */
Result<GDALDatasetH> normaliseLongitudes(GDALDatasetH ds, DatasetChain& chain,
                                         const std::string& sourceName);

/**
 * @brief Georeference a source for placement (shared by planGrid and placeOnGrid): the returned
 * dataset (owned by `chain`) has a geotransform and, when one is known, a CRS, with longitudes
 * normalised. Resolves the deprecated `opt.crs` into `opt.assignCrs` (CRS-less source) or
 * `opt.toCrs` (source with a CRS, CF lon/lat axes count as one). A CRS-less source on CF lon/lat
 * axes is WGS 84; assigning a projected CRS to such degrees, or a geographic CRS to coordinates
 * outside -180..360 / -90..90 (longitudes of a whole-globe grid excepted), is IMPORT_BAD_CRS. A
 * curvilinear source (Curvilinear.h) is returned as it is, `crs` being its geolocation arrays' and
 * `*geolocation` set: it can only be warped (and --assign-crs does not apply to it).
 */
struct Geolocation;
Result<GDALDatasetH> georeference(GdalDataset source, PlaceOptions& opt,
                                  std::optional<StoreCrs>& crs, DatasetChain& chain,
                                  std::optional<Geolocation>* geolocation = nullptr);

/** @brief Regional limit: a geographic source wider or taller than this goes to a global CRS. */
constexpr double kRegionalSpanDeg = 20.0;

/**
 * @brief The automatic target CRS of a geographic source: the UTM zone (WGS 84) of its centre
 * when it spans at most kRegionalSpanDeg in longitude and latitude and stays within UTM's
 * 84 S..84 N; otherwise an equidistant cylindrical projection (plate carrée in metres) on
 * WGS 84 centred on the data's central meridian, EPSG:4087 when that meridian is 0 (so a grid
 * crossing the dateline stays in one piece).
 */
StoreCrs autoTargetCrs(const LonLatExtent& e);

/** @brief The stated working-memory budget of one import (bytes); `--max-memory MB` changes it. */
constexpr std::int64_t kDefaultImportBudget = std::int64_t(2) << 30;

/**
 * @brief Pre-flight estimate of an import's working set for a window `width` pixels wide:
 * the finest-level row strip (tileSize + 1 rows of float samples, the double read buffer and the
 * per-tile posts and encoded blobs, 24 bytes a sample), GDAL's block cache, plus `extraBytes`
 * (e.g. a raster held whole for --fill-voids).
 */
std::int64_t estimateImportBytes(std::int64_t width, int tileSize, std::int64_t extraBytes = 0);

/** @brief IMPORT_TOO_LARGE naming the source when the estimate exceeds `budget`. */
Diagnostics checkImportBudget(std::int64_t width, std::int64_t height, int tileSize,
                              std::int64_t extraBytes, std::int64_t budget,
                              const std::string& sourceName);

}  // namespace kiosk::import
