#pragma once

// Steps every import kind shares: placing a GDAL source on the store grid (defining the grid
// for a new store) and building a scalar layer's pyramid. Internal to the import module.

#include "runtime/core/Progress.h"
#include "runtime/import/GdalRaster.h"
#include "runtime/import/Importer.h"
#include "runtime/import/Pyramid.h"
#include "runtime/io/StoreWriter.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace kiosk::import {

/** @brief The lower-case extension of `path`, with its dot (".sww"). */
std::string lowerExt(const std::string& path);

/** @brief The scene extent (x0, y0, x1, y1) of a window on the grid's finest level. */
void windowExtent(const io::TileGrid& g, const GridWindow& w, double& x0, double& y0, double& x1,
                  double& y1);

/**
 * @brief Place a GDAL source on the store grid (or `onGrid`, a refinement of it), defining the
 * grid first for a new store. CRS assumptions are added to `warnings`.
 */
Result<PlacedSource> placeSource(io::StoreWriter& w, GdalDataset src, const PlaceOptions& po,
                                 int tileSize, Diagnostics& warnings,
                                 const io::TileGrid* onGrid = nullptr);

/** @brief The placement options an import's command line gives for `source`. */
PlaceOptions placeOptions(const ImportOptions& o, const std::string& source);

/** @brief What a scalar layer (elevation or a sequence frame) is stored as. */
struct ScalarImport {
    std::string table;
    io::LayerKind kind = io::LayerKind::Elevation;
    std::string units;
    bool categorical = false;
    double minStep = 1.0 / 256.0;
    std::optional<double> nodata;
};

/**
 * @brief Create the scalar layer `si` and fill its pyramid from `rows` (an elevation layer also
 * gets its simplified tile meshes).
 */
Result<PyramidResult> importScalarLayer(io::StoreWriter& w, const PlacedSource& ps,
                                        const ScalarRowSource& rows,
                                        std::optional<std::pair<double, double>> range,
                                        const ScalarImport& si, const ImportOptions& o,
                                        const std::string& src, Progress& progress);

/**
 * @brief Frames appended to a sequence must come after the ones it holds: the error (against
 * `file`) when `firstNew` is not after the last of `existing`, else none.
 */
Diagnostics checkAppendsAfter(const std::vector<double>& existing, double firstNew,
                              const std::string& file, const std::string& sequence);

/**
 * @brief Frame `index` of `sequence` at `epochSeconds`: its scalar layer (table
 * "<sequence>_f<index>") built from `rows`, then its row in the sequence's frame list.
 */
Diagnostics importSequenceFrame(io::StoreWriter& w, const PlacedSource& ps,
                                const ScalarRowSource& rows,
                                std::optional<std::pair<double, double>> range,
                                const std::string& sequence, int index, double epochSeconds,
                                const std::string& units, bool categorical, const ImportOptions& o,
                                const std::string& src, Progress& progress);

// The import kinds Importer.cpp dispatches to (each inside its temporary-store transaction).
/** @brief `import elevation` of a GDAL raster or an SWW file's bed (RasterImport.cpp). */
Diagnostics importElevationSource(const std::string& source, const ImportOptions& o);
/** @brief `import imagery` of a GDAL raster (RasterImport.cpp). */
Diagnostics importImagerySource(const std::string& source, const ImportOptions& o);
/** @brief The bed of an ANUGA SWW model on the grid its depth sequence uses (SwwImport.cpp). */
Diagnostics importSwwElevation(const std::string& source, const ImportOptions& o);
/** @brief An SWW model's depth or velocity as a sequence (SwwImport.cpp). */
Diagnostics importSww(const std::string& source, const ImportOptions& o);

}  // namespace kiosk::import
