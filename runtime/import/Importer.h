#pragma once

#include "runtime/core/Result.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace kiosk::import {

/** @brief Everything `geokiosk import` accepts (docs/cli.md); defaults match the CLI. */
struct ImportOptions {
    std::filesystem::path store;
    std::string name;                ///< layer / sequence name (elevation default "elevation")
    std::optional<std::string> crs;  ///< --crs (deprecated): assign if CRS-less, else target
    std::optional<std::string> assignCrs;  ///< --assign-crs: the source's CRS
    std::optional<std::string> toCrs;      ///< --to-crs: a new store's CRS (warp target)
    std::optional<int> band;               ///< --band: elevation band (1-based)
    std::int64_t memoryBudget = std::int64_t(2) << 30;  ///< --max-memory (bytes)
    std::optional<double> pixelSize;      ///< --pixel-size: for sources without georeferencing
    double zScale = 1.0;                  ///< --z-scale: raw value multiplier
    std::optional<std::string> units;     ///< --units m|ft (elevation) or free text (sequence)
    std::optional<std::string> timesCsv;  ///< --times
    std::string variable;                 ///< --variable (NetCDF)
    double wetThreshold = 0.01;           ///< --wet-threshold (SWW), metres
    std::optional<double> start;          ///< --start: time of frame 0 when times are numbered
    double step = 3600;                   ///< --step seconds between numbered frames
    std::optional<std::string> gridLike;  ///< --like: georeferencing for bare CSV grids
    std::optional<bool> categorical;      ///< --categorical (auto for Cell2Fire grids)
    bool jpeg = false;                    ///< --jpeg: opaque imagery tiles as JPEG
    bool quiet = false;                   ///< no progress output
    /** @brief --fill-voids: interpolate interior nodata holes (SRTM voids) before tiling, with
     *  GDAL's FillNodata (inverse distance, up to 100 pixels). Holds the raster in memory. */
    bool fillVoids = false;
    int threads = 2;
    int tileSize = 256;
    /** @brief Test hook: fail after this many tiles (< 0 = off). */
    std::int64_t failAfterTiles = -1;
};

/**
 * @brief The import commands. Each writes into `STORE.tmp-XXXXXX` (a copy of the store when it
 * exists) and renames it over the store only on success: on any error the temporary file is
 * removed and the store is untouched. Returned diagnostics name the file; warnings may accompany
 * success. Thread: call from one thread; uses `threads` workers internally.
 */
Diagnostics importElevation(const std::string& source, const ImportOptions& options);
Diagnostics importImagery(const std::string& source, const ImportOptions& options);
Diagnostics importSequence(const std::vector<std::string>& sources, const ImportOptions& options);

/** @brief A time embedded in a file name: 20240131T0600, 2024-01-31T06:00:00, 202401310600. */
std::optional<double> timeFromFileName(const std::string& fileName);

/**
 * @brief Read a times CSV: one frame per line, either `time` or `file,time` (ISO 8601 UTC or
 * epoch seconds); a header line is skipped. IMPORT_TIMES naming file and line.
 */
Result<std::vector<std::pair<std::string, double>>> readTimesCsv(const std::string& path);

/** @brief Strictly increasing, or IMPORT_TIMES_UNSORTED / IMPORT_TIMES_DUPLICATE naming files. */
Diagnostics checkTimes(const std::vector<double>& times, const std::vector<std::string>& files);

/** @brief Parse a Cell2Fire style numeric CSV grid (comma or space separated). */
Result<std::vector<float>> readCsvGrid(const std::string& path, int& width, int& height);

}  // namespace kiosk::import
