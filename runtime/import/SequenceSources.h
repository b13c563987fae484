#pragma once

// The frames a sequence import is given (files, directories, NetCDF bands) and their times.
// Internal to the import module.

#include "runtime/core/Result.h"
#include "runtime/import/Importer.h"

#include <optional>
#include <string>
#include <vector>

namespace kiosk::import {

/** @brief One frame of a sequence import: a raster band, or a CSV grid. */
struct Frame {
    std::string file;  ///< what diagnostics name
    std::string open;  ///< what GDAL opens
    int band = 1;
    std::optional<double> time;
    bool csvGrid = false;
};

/**
 * @brief The georeferenced raster a CSV grid lies on: an `elevation.asc` in its folder or up to
 * two folders above (a Cell2Fire landscape); none when there is none.
 */
std::optional<std::string> findLike(const std::string& file);

/**
 * @brief Every frame of `sources` (directories expand to their files in name order; a NetCDF
 * file gives one frame per band) with its time: the data's own (CF time), --times, a date-time
 * in the file name, or numbered from --start.
 */
Result<std::vector<Frame>> expandSources(const std::vector<std::string>& sources,
                                         const ImportOptions& o);

}  // namespace kiosk::import
