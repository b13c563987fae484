#pragma once

#include "runtime/core/Result.h"
#include "runtime/import/Pyramid.h"
#include "runtime/io/StoreTypes.h"

#include <gdal.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

// GDAL plumbing of the importer: opening sources, resolving CRSs, planning a store grid, and
// streaming a source onto a grid window (directly when aligned, through a warped VRT otherwise).
namespace kiosk::import {

struct GdalDatasetDeleter {
    void operator()(void* h) const noexcept {
        if (h) GDALClose(GDALDatasetH(h));
    }
};
using GdalDataset = std::unique_ptr<void, GdalDatasetDeleter>;

inline GDALDatasetH raw(const GdalDataset& d) {
    return GDALDatasetH(d.get());
}

/** @brief Register drivers, quiet GDAL's own stderr, bound its block cache (bounded RSS). */
void initGdal();

/** @brief Last GDAL error message, or `fallback`. */
std::string gdalError(const std::string& fallback);

/** @brief Open a raster; IMPORT_UNREADABLE naming the file. */
Result<GdalDataset> openRaster(const std::string& path);

/** @brief A store CRS: the gpkg_spatial_ref_sys row it becomes. */
struct StoreCrs {
    int srsId = 0;
    std::string name;
    std::string wkt;  ///< WKT1 (GeoPackage 1.3 definition column)
};

/** @brief A local engineering CRS in metres for inputs without one. */
StoreCrs localCrs();
/** @brief Describe a user CRS string (EPSG:N, WKT, PROJ); IMPORT_BAD_CRS on failure. */
Result<StoreCrs> crsFromUser(const std::string& text, const std::string& option = "--crs");
/** @brief Same CRS (OSRIsSame), for WKT/PROJ/EPSG texts. */
bool sameCrs(const std::string& a, const std::string& b);
/** @brief True for a geographic (longitude/latitude) CRS. */
bool isGeographicCrs(const std::string& wkt);
/** @brief Describe a dataset's CRS; nullopt if it has none. */
std::optional<StoreCrs> crsOfDataset(GDALDatasetH ds);
/** @brief UTM zone CRS (WGS 84) containing lon/lat. */
StoreCrs utmCrsFor(double lon, double lat);

/** @brief Options that shape how a source is placed on a grid. */
struct PlaceOptions {
    std::optional<std::string> crs;        ///< --crs (deprecated): assign if CRS-less, else target
    std::optional<std::string> assignCrs;  ///< --assign-crs: the source's CRS (overrides its own)
    std::optional<std::string> toCrs;      ///< --to-crs: the new store's CRS
    std::optional<double> pixelSize;       ///< --pixel-size for sources without georeferencing
    std::int64_t memoryBudget = std::int64_t(2) << 30;  ///< --max-memory, bytes
    bool nearest = false;  ///< categorical data: nearest-neighbour resampling
    bool imagery = false;  ///< keep bytes and add an alpha band
    std::string sourceName;
};

/**
 * @brief Datasets that read from each other (source <- VRT copy <- warped VRT), closed newest
 * first: a VRT must never outlive the dataset it reads.
 */
class DatasetChain {
public:
    DatasetChain() = default;
    DatasetChain(DatasetChain&&) = default;
    DatasetChain& operator=(DatasetChain&& o) noexcept {
        clear();
        mItems = std::move(o.mItems);
        return *this;
    }
    ~DatasetChain() { clear(); }
    GDALDatasetH add(GdalDataset d) {
        mItems.push_back(std::move(d));
        return raw(mItems.back());
    }
    void clear() {
        while (!mItems.empty()) mItems.pop_back();
    }

private:
    std::vector<GdalDataset> mItems;
};

/** @brief A source ready to stream onto a grid window. */
struct PlacedSource {
    DatasetChain chain;         ///< owns the source and every VRT over it
    GDALDatasetH ds = nullptr;  ///< what to read
    int xOff = 0, yOff = 0;     ///< dataset pixel of the window's (0,0)
    GridWindow window;
    std::vector<std::string> warnings;
};

/**
 * @brief Plan a new store grid from a source: geographic sources (including CRS-less CF lon/lat
 * grids) go to autoTargetCrs (GeoTarget.h) unless `opt.toCrs` names one; the finest level has the
 * source's pixel size, or, when warped, GDAL's suggested square pixel size computed in the target
 * CRS; level 0 is one tile. IMPORT_TOO_LARGE when the pre-flight estimate exceeds the budget.
 */
struct PlannedSource {
    io::TileGrid grid;
    PlacedSource placed;  ///< the whole (warped) source as the grid's window
};
Result<PlannedSource> planGrid(GdalDataset source, const PlaceOptions& opt, int tileSize);

/** @brief Place a source on an existing grid (IMPORT_EXTENT_MISMATCH if it misses it). */
Result<PlacedSource> placeOnGrid(GdalDataset source, const io::TileGrid& grid,
                                 const PlaceOptions& opt);

/**
 * @brief Scalar rows of band `band` (1-based) of a placed source: raw * bandScale + bandOffset,
 * times `factor`; the band's nodata -> NaN; NaN or infinity that is not nodata is IMPORT_NAN.
 */
ScalarRowSource scalarRows(const PlacedSource& p, int band, double factor,
                           const std::string& sourceName);
/** @brief RGBA rows of a placed imagery source (gray, gray+alpha, RGB, RGBA). */
RgbaRowSource rgbaRows(const PlacedSource& p, const std::string& sourceName);

/** @brief Approximate min/max of a band after scale/offset, nullopt if no valid pixel. */
std::optional<std::pair<double, double>> bandRange(GDALDatasetH ds, int band);

/** @brief Quantisation step: the smallest power of two >= max(minStep, range / 65534 * margin). */
double chooseScale(double range, double minStep);

/** @brief An in-memory single-band float dataset (CSV grids, tests). */
GdalDataset memRaster(const std::vector<float>& values, int width, int height,
                      const std::array<double, 6>& geoTransform, const std::string& wkt,
                      std::optional<double> nodata);

}  // namespace kiosk::import
