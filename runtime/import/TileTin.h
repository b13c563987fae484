#pragma once

#include "runtime/core/Result.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/io/TinBlob.h"
#include "runtime/math/Glm.h"

#include <cstdint>
#include <functional>
#include <vector>

// One tile's local TIN (Baumann et al. 2000, "Hybrid Terrain Models": a grid cell refined by a
// TIN whose border matches the grid), built with CGAL's constrained Delaunay triangulation.
// Coordinates are the tile's post coordinates: u = column east, v = row south, post (0, 0) the
// north-west one; heights in metres.
namespace kiosk::import {

/** @brief A polyline in post coordinates with a height at every point. */
using TinPolyline = std::vector<glm::dvec3>;

/** @brief What a tile's TIN is made of. */
struct TileTinInput {
    const io::RasterTile* posts = nullptr;  ///< (n + 1)^2 posts of the tile, NaN = nodata
    double pixelX = 1.0, pixelY = 1.0;      ///< post spacing (metres), for the normals
    /**
     * @brief Constrained edges (breaklines, a model's triangle edges), already clipped to
     * [kTinBorderInset, n - kTinBorderInset]^2 (clipPolyline) so the border stays the posts'.
     */
    std::vector<TinPolyline> lines;
    /** @brief Per post: 1 = left out (next to a line, or under a model mesh the lines give). */
    std::vector<std::uint8_t> replaced;
    /**
     * @brief Whether a point (u, v) is surface although the grid has no data there (inside a
     * model mesh); empty: only where the grid has data.
     */
    std::function<bool(double u, double v)> covered;
    /** @brief Posts not left out are kept within this vertical distance (metres). */
    double tolerance = 0.1;
};

/** @brief A built TIN and what it took. */
struct TileTinResult {
    io::TinMesh mesh;
    double maxError = 0.0;          ///< largest |TIN - post| over the posts not left out (metres)
    int rounds = 0;                 ///< insertion rounds until every post was within tolerance
    std::size_t lineVertices = 0;
};

/** @brief How far (post intervals) constrained edges stay from the tile border. */
inline constexpr double kTinBorderInset = 0.5;

/**
 * @brief Build the TIN: the valid border posts (all of them: the seam with the neighbouring
 * grid tiles is the posts'), the lines' vertices with their segments as constrained edges, and
 * the posts not left out inserted greedily (each round, in every triangle, the post farthest
 * from the surface; Baumann's "TIN approximation") until every one is within `tolerance`.
 * Triangles over nodata (not `covered`) are dropped, as the grid drops them. Normals: a post's
 * from its neighbouring posts as the grid mesh computes them (so the seam shades alike), other
 * vertices the area-weighted mean of their triangles'. TERRAIN_TIN when the triangulation cannot
 * be stored exactly (lines crossing closer than 1/1024 post).
 */
Result<TileTinResult> buildTileTin(const TileTinInput& input);

/**
 * @brief The parts of `line` (post coordinates) inside [lo, hi]^2, heights interpolated at the
 * cut points; appended to `out`.
 */
void clipPolyline(const TinPolyline& line, double lo, double hi, std::vector<TinPolyline>& out);

}  // namespace kiosk::import
