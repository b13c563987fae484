#pragma once

#include "runtime/core/Progress.h"
#include "runtime/core/Result.h"
#include "runtime/io/StoreWriter.h"
#include "runtime/math/Glm.h"

#include <cstdint>
#include <string>
#include <vector>

// Local TINs in the grid (Baumann et al. 2000, "Hybrid Terrain Models"; docs/terrain.md "Local
// TINs"): the tiles that lines or a model mesh cross, at the levels where the grid cannot keep
// them within the tile's error bound, get a constrained Delaunay TIN (TileTin.h) that the loader
// draws instead of the grid mesh. Shared by `import breaklines` and `import model-mesh`.
namespace kiosk::import {

/** @brief What the TINs are built from, in the store's CRS (metres; z in metres). */
struct TinFeatures {
    /** @brief Constrained polylines (breaklines; a model's triangle edges), every point with z. */
    std::vector<std::vector<glm::dvec3>> lines;
    /**
     * @brief A model mesh whose triangles replace the grid under them (empty for breaklines):
     * points with z and counter-clockwise or clockwise index triples.
     */
    std::vector<glm::dvec3> meshPoints;
    std::vector<std::uint32_t> meshTriangles;
};

/** @brief Where the TINs go. */
struct LocalTinOptions {
    std::string elevation = "elevation";  ///< elevation layer whose tiles get TINs
    std::string source;                   ///< the import's --name, stored with each TIN
    /**
     * @brief Every finest-level tile the features cross gets a TIN, within the error bound or
     * not (a model mesh: the terrain shows the model's own triangles); coarser levels still
     * follow the error rule.
     */
    bool everyFinestTile = false;
    int threads = 2;
};

/** @brief What storeLocalTins wrote. */
struct LocalTinStats {
    std::int64_t tiles = 0;          ///< tiles with a TIN
    std::int64_t rows = 0;           ///< TINs stored (kiosk_tile_tins rows)
    std::int64_t tilesChecked = 0;   ///< tiles the features cross (over the levels visited)
    std::int64_t tinTriangles = 0;   ///< over all TIN tiles, tier 0
    std::int64_t gridTriangles = 0;  ///< the same tiles' grid meshes (tier 0), for comparison
    std::int64_t blobBytes = 0;
    int finestLevel = -1, coarsestLevel = -1;  ///< levels that got TINs (-1: none)
    double maxError = 0.0;  ///< worst |TIN - post| over the posts tier-0 TINs keep (metres)
};

/**
 * @brief Build and store the TINs for `features` on the writer's open store (one transaction,
 * `withTempStore`). From the finest level up: a tile the features cross gets a TIN when the
 * grid (bilinear over its posts) misses the features' heights, sampled along them every quarter
 * post, by more than the tile's error bound (stored error e + tier-0 tolerance); the first
 * level where no crossed tile needs one ends the climb. A tile's TIN is built at tier 0 (its
 * tolerance t0); the loader draws it for every coarser tier as well. Earlier TINs of
 * the same source are replaced; a tile whose TIN came from another source gets the new one with a
 * warning (IMPORT_TIN_REPLACED). Errors: IMPORT_NO_ELEVATION, IMPORT_TIN_OUTSIDE (no tile with data
 * is crossed), TERRAIN_TIN naming the tile.
 */
Result<LocalTinStats> storeLocalTins(io::StoreWriter& writer, const TinFeatures& features,
                                     const LocalTinOptions& options, Progress& progress);

/**
 * @brief Heights for 2D lines from the elevation layer's finest posts: each line densified to
 * one point per post spacing, z the bilinear interpolation of the posts; parts over nodata or
 * outside the grid are cut out. `lines` come in with NaN z.
 */
Diagnostics heightsFromElevation(io::StoreWriter& writer, const std::string& elevation,
                                 std::vector<std::vector<glm::dvec3>>& lines);

}  // namespace kiosk::import
