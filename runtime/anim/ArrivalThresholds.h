#pragma once

#include <optional>
#include <span>
#include <vector>

namespace kiosk::anim {

/**
 * @brief Per-pixel arrival thresholds for `interpolate: "arrival"` when the data has no
 * arrival-time raster, derived from the two class rasters of a frame pair (loader thread; the
 * result is uploaded as one extra R16F/R32F texture per tile and frame pair).
 *
 * For a pixel whose class changes to c between frame 0 and frame 1:
 *   d0 = distance (pixels) to the nearest pixel already of class c in frame 0 (the old front),
 *   d1 = distance to the nearest pixel of class c in neither frame (just beyond the new front),
 *   threshold = d0 / (d0 + d1),
 * so with `value = alpha >= threshold ? v1 : v0` the class boundary sweeps from the old
 * perimeter to the new one as alpha goes from 0 to 1, at even speed, never blending classes.
 * If class c is absent from frame 0 (an ignition), pixels deep inside the new patch switch
 * first: threshold = 1 - d1 / (max d1 of that class + 1). If neither distance is defined inside
 * the raster (the patch covers it all), the threshold is 0.5. Unchanged pixels get 0.
 *
 * Distances are exact Euclidean (Felzenszwalb-Huttenlocher) within the given raster only: run
 * it on a tile with a border of neighbour pixels, or accept small seams at tile edges.
 * NaN is nodata: replaced by `nodataAs` when given, else treated as a class of its own.
 * `v0` and `v1` are row-major width x height; mismatched sizes give an empty `out`.
 */
void computeArrivalThresholds(std::span<const float> v0, std::span<const float> v1, int width,
                              int height, std::optional<float> nodataAs, std::vector<float>& out);

}  // namespace kiosk::anim
