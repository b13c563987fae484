#pragma once

#include "runtime/core/Diagnostics.h"

#include <filesystem>
#include <string>

// `geokiosk import breaklines` and `geokiosk import model-mesh` (docs/cli.md, docs/terrain.md
// "Local TINs"): local TINs in an existing store's elevation grid (LocalTins.h).
namespace kiosk::import {

struct LocalTinImportOptions {
    std::filesystem::path store;
    std::string elevation = "elevation";  ///< --elevation: the layer whose tiles get TINs
    std::string name;                     ///< --name: the TINs' source (default: file stem)
    int threads = 2;
    bool quiet = false;
};

/**
 * @brief Lines from a vector file GDAL/OGR reads (GeoPackage, GeoJSON, ...): every LineString
 * and MultiLineString of every layer, reprojected to the store's CRS. 3D lines keep their Z;
 * 2D lines take their heights from the elevation layer (heightsFromElevation). Errors (one line
 * each): IMPORT_UNREADABLE (not a vector file OGR opens), IMPORT_NO_CRS (a layer without a
 * CRS), IMPORT_BREAKLINES (a geometry that is not a line, no lines at all, a coordinate that
 * does not reproject), IMPORT_TIN_OUTSIDE (no line over the elevation's data). Atomic.
 */
Diagnostics importBreaklines(const std::string& lines, const LocalTinImportOptions& options);

/**
 * @brief An ANUGA SWW model's own mesh (points, triangles, bed elevation of step 0) as the TINs
 * of the tiles it covers: its triangle edges are the constrained lines and the posts under it
 * are left out, so the terrain shows the model's triangles. The SWW's coordinates are taken in
 * the store's CRS (as `import elevation X.sww` does); a UTM zone in the file that is not the
 * store's is IMPORT_CRS_MISMATCH. Errors as SwwMesh::open, IMPORT_TIN_OUTSIDE.
 */
Diagnostics importModelMesh(const std::string& sww, const LocalTinImportOptions& options);

}  // namespace kiosk::import
