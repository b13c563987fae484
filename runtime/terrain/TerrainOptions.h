#pragma once

#include "runtime/io/StoreTypes.h"

#include <algorithm>
#include <cmath>

namespace kiosk::terrain {

/**
 * @brief Quality knobs shared by the selector (render thread) and the mesh builder (loader
 * thread). Both must use the same values: the selector adds the TIN tolerance of a level to
 * that level's stored geometric error when it checks the screen-space bound. See docs/terrain.md.
 */
struct TerrainOptions {
    /** @brief Max visual geometric error in pixels (Döllner's gamma_user). 0 = full resolution. */
    double tauGeom = 1.0;
    /** @brief Max projected texel size in pixels (Döllner's tau_user). */
    double tauTex = 1.0;
    /**
     * @brief TIN tolerance of a tile's mesh as a fraction of the tile's stored geometric error
     * (the error bound then grows by this factor: gamma uses e * (1 + factor)). Wahl's tiles
     * simplify within their level's error bound in the same proportional way.
     */
    double tinToleranceFactor = 0.5;
    /**
     * @brief Floor of the TIN tolerance in metres: lets nearly flat tiles (flood plains with
     * centimetre noise, finest-level tiles whose error is 0) collapse to a few triangles.
     * It is part of the error bound, so close-ups are exact to this many metres.
     */
    double tinToleranceMin = 0.1;
    /** @brief Finest geometry everywhere and exact meshes (the fidelity reference). */
    bool fullResolution = false;
    /**
     * @brief Upper bound (metres) on the vertical error of any tile that may be drawn next to
     * a tile, including coarse ancestors drawn while neighbours load. Skirts hang at least this
     * far. The application sets it from the root tile's stats (error + tolerance) when known;
     * 0 means "only the tile's own error" (cracks then stay under the pixel bound, Wahl 5.2).
     */
    double neighbourErrorBound = 0.0;

    /**
     * @brief How many levels a texture layer may refine beyond the finest elevation level.
     * Such nodes draw the cells of their elevation ancestor's mesh under the node, clipped to
     * the node (TileMesh cells, MeshCells.h): about one ancestor mesh's work in all, not one
     * per descendant.
     */
    int textureLevelsBeyondGeometry = 1;

    /**
     * @brief Coarser meshes of the same tile for tiles seen from afar ("tolerance tiers"): tier
     * k > 0 is built with tinTolerance(e) * 2^k. The selector picks, for the node whose mesh
     * meets tauGeom, the coarsest tier that still does ((e + t_k) ppm(d) <= tauGeom), so a tile
     * of the finest level (e = 0, t = tinToleranceMin) seen from 20 km is not meshed to 0.1 m.
     * Tier k is requested as TileKey::frame = k of the elevation layer. 0 disables the tiers.
     */
    int toleranceTiers = 10;

    /** @brief Options for the fidelity reference: finest level everywhere, zero tolerance. */
    static TerrainOptions fullResolutionReference() {
        TerrainOptions o;
        o.tauGeom = 0.0;
        o.tauTex = 0.0;
        o.tinToleranceFactor = 0.0;
        o.tinToleranceMin = 0.0;
        o.fullResolution = true;
        return o;
    }

    /** @brief Post spacing of a level in metres (max of x and y); 0 for a level not in the grid. */
    static double postSpacing(const io::TileGrid& grid, int level) {
        if (level < 0 || level > grid.maxLevel()) return 0.0;
        const io::TileMatrix& m = grid.levels[std::size_t(level)];
        return std::max(m.pixelXSize, m.pixelYSize);
    }

    /** @brief TIN tolerance (metres) for a tile whose stored geometric error is `tileError`. */
    double tinTolerance(double tileError) const {
        if (fullResolution) return 0.0;
        return std::max(std::max(0.0, tinToleranceFactor) * std::max(0.0, tileError),
                        std::max(0.0, tinToleranceMin));
    }

    /** @brief TIN tolerance (metres) of tolerance tier `tier` (0: tinTolerance(tileError)). */
    double tinTolerance(double tileError, int tier) const {
        const double base = tinTolerance(tileError);
        if (tier <= 0 || fullResolution) return base;
        return std::ldexp(base, std::min(tier, 30));
    }

    /** @brief Highest tolerance tier the selector may ask for (0 at full resolution). */
    int maxToleranceTier() const { return fullResolution ? 0 : std::clamp(toleranceTiers, 0, 30); }

    /**
     * @brief Skirt depth (metres) for a tile of `level` whose stored error is `tileError`:
     * the vertical gap to any neighbour is at most (own error + tolerance) + (neighbour's), so
     * the skirt covers both, plus one post spacing so rasterisation never shows a seam.
     */
    double skirtDepth(const io::TileGrid& grid, int level, double tileError, int tier = 0) const {
        const double own = std::max(0.0, tileError) + tinTolerance(tileError, tier);
        return own + std::max(own, neighbourErrorBound) + postSpacing(grid, level);
    }
};

}  // namespace kiosk::terrain
