#pragma once

// Helpers the importer's tests share (ImportTest, ImportSequenceTest, ImportSwwTest,
// ImportErrorsTest): writing small rasters, reading a store back, looking for leftovers.

#include "runtime/io/StoreReader.h"

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace kiosk::import::test {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/** @brief A fresh, empty folder for one test. */
std::filesystem::path testDir();

/** @brief `rel` under ../shared/data (or $KIOSK_SHARED_DATA); "" when absent. */
std::string sharedData(const std::string& rel);

/** @brief A one-band Float32 GeoTIFF (EPSG `epsg`, 0: no CRS). Fails the test on error. */
void writeTiff(const std::filesystem::path& p, int w, int h, const double gt[6], int epsg,
               const std::vector<float>& v, std::optional<double> nodata = std::nullopt,
               const char* unit = nullptr);

/** @brief A 600 x 520 DEM in UTM 10N, 30 m pixels, with a nodata block; its values if asked. */
std::filesystem::path makeDem(const std::filesystem::path& dir,
                              std::vector<float>* values = nullptr);

/** @brief The finest level of a scalar layer assembled into one array (window from 0,0). */
std::vector<float> finestArray(io::StoreReader& r, const std::string& layer, int w, int h,
                               int frame = -1);

/** @brief What `gdallocationinfo -valonly` reads from the store at pixels `px`. */
std::vector<double> gdalLocationValues(const std::filesystem::path& store,
                                       const std::vector<std::pair<int, int>>& px);

/** @brief GDAL's own GeoPackage validator (python3-gdal), when installed: "" if valid or absent. */
std::string validateGpkg(const std::filesystem::path& store);

/** @brief Temporary stores (".tmp-") left in `dir`. */
std::vector<std::string> leftovers(const std::filesystem::path& dir);

/** @brief A file's whole contents. */
std::string fileBytes(const std::filesystem::path& p);

}  // namespace kiosk::import::test
