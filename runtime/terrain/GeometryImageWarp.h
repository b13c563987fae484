#pragma once

#include "runtime/math/Glm.h"

#include <vector>

namespace kiosk::terrain {

/**
 * @brief An importance map (Dachsbacher & Stamminger 2004, "DS04", §3.1): the desired density of
 * grid samples (samples per metre, isotropic) over an axis-aligned world rectangle, given on a
 * regular `size` x `size` lattice from corner to corner and bilinearly interpolated between.
 * Values must be > 0 (the warp divides by them).
 */
struct ImportanceMap {
    glm::dvec2 min{0.0}, max{1.0};
    int size = 0;               ///< lattice points per side (>= 2)
    std::vector<float> values;  ///< row-major, row 0 at min.y

    /** @brief Bilinear value at world position `p` (clamped to the rectangle). */
    double at(const glm::dvec2& p) const;
};

/**
 * @brief A geometry image's warping function Phi (DS04 §3.2) at `n` x `n` samples: the world
 * xy position of grid sample (s, t), row-major with t = row. Rows and columns keep their order
 * (no folds); the rectangle's border samples stay on its border.
 */
struct WarpGrid {
    int n = 0;
    std::vector<glm::dvec2> points;

    const glm::dvec2& at(int s, int t) const {
        return points[std::size_t(t) * std::size_t(n) + std::size_t(s)];
    }
    glm::dvec2& at(int s, int t) {
        return points[std::size_t(t) * std::size_t(n) + std::size_t(s)];
    }
};

/** @brief The regular (unwarped) grid of `n` x `n` samples over [min, max]. */
WarpGrid uniformWarpGrid(const glm::dvec2& min, const glm::dvec2& max, int n);

/**
 * @brief One row pass then one column pass of DS04's separable warp (§3.3, Fig. 5): along every
 * row (then every column) the samples are moved along the line through them so that the line's
 * importance mass between neighbours is equal, i.e. the spacing becomes proportional to
 * 1 / I. The importance is re-evaluated at the moved positions between the passes (the paper
 * resamples the importance map with the image). The end samples of each line stay fixed.
 * `substeps` evaluations of I per segment integrate the importance along it.
 */
void warpPass(WarpGrid& grid, const ImportanceMap& importance, int substeps = 4);

/**
 * @brief `iterations` warp passes starting from the regular grid over the importance map's
 * rectangle (DS04 notes that further row/column passes improve the result; each costs
 * O(n^2 * substeps)). 0 iterations: the regular grid of the same vertex count.
 */
WarpGrid warpGeometryImage(const ImportanceMap& importance, int n, int iterations);

/**
 * @brief Local sample spacing of grid sample (s, t): the mean distance to its row and column
 * neighbours (one-sided at the border), in metres. What the importance asks for is
 * proportional to 1 / I there.
 */
double sampleSpacing(const WarpGrid& grid, int s, int t);

/** @brief The largest distance from sample (s, t) to its direct neighbours (DS04 Eq. 1's d_ij). */
double maxNeighbourDistance(const WarpGrid& grid, int s, int t);

/**
 * @brief Smooth the map in place with `passes` of a [1 2 1] / 4 filter per axis. The separable
 * warp moves neighbouring lines independently; a smooth importance keeps neighbouring lines
 * alike, so the grid does not fold (DS04's "smoothed safety transition zone").
 */
void smoothImportance(ImportanceMap& map, int passes);

/**
 * @brief The triangle diagonal of grid cell (s, t) that keeps both triangles counter-clockwise:
 * 0 for (s,t)-(s+1,t+1), 1 for (s+1,t)-(s,t+1), -1 when neither does (a folded cell).
 */
int cellDiagonal(const WarpGrid& grid, int s, int t);

/** @brief True when every grid cell has a diagonal that splits it into two proper triangles. */
bool warpGridUnfolded(const WarpGrid& grid);

}  // namespace kiosk::terrain
