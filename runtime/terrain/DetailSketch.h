#pragma once

#include "runtime/math/Camera.h"
#include "runtime/math/Glm.h"
#include "runtime/terrain/GeometryImageWarp.h"

#include <cstdint>
#include <vector>

namespace kiosk::terrain {

/**
 * @brief Bounds of the procedural detail (docs/terrain.md §7). The noise is normalised so its
 * absolute value never exceeds 1; the displacement is amplitude * noise with
 *   amplitude = min(kRoughnessGain * roughness, kErrorFraction * E)
 * where roughness is the data's post-scale relief (|z - mean of the 4 neighbours|) and E the
 * geometric error of the drawn tile's parent: what one more level of refinement changed in the
 * data at that place, the magnitude of the missing next level of detail.
 */
inline constexpr double kDetailErrorFraction = 0.25;
inline constexpr double kDetailRoughnessGain = 1.0;
/** @brief Noise octaves above the data's post frequency (DS04 §4.1: f_k = 2^(k-1) / d0). */
inline constexpr int kDetailOctaves = 4;

/**
 * @brief The "sketch map" of DS04 §2: the data surface over the detail region at the data's post
 * spacing, with the amplitude bound of the procedural detail per post. Post (i, j) is at
 * min + (i, j) * spacing (row j = 0 at the south edge). Heights come from what the quadtree
 * draws there (so the hand-over matches); NaN where nothing is drawn.
 */
struct DetailSketch {
    glm::dvec2 min{0.0};
    double spacing = 1.0;
    int width = 0, height = 0;
    std::vector<float> heights;
    std::vector<float> amplitude;  ///< metres, >= 0
    std::vector<float> cap;        ///< kDetailErrorFraction * E per post (input of amplitude)
    /** @brief Optional: the drawn surface's normals at the posts (else from the heights). */
    std::vector<glm::vec3> normals;

    glm::dvec2 max() const { return min + glm::dvec2(width - 1, height - 1) * spacing; }
    std::size_t index(int i, int j) const {
        return std::size_t(j) * std::size_t(width) + std::size_t(i);
    }
    /** @brief Bilinear height at `p` (clamped to the sketch); NaN if a corner post is NaN. */
    double heightAt(const glm::dvec2& p) const;
    double amplitudeAt(const glm::dvec2& p) const;
    /** @brief Unit normal of the bilinear surface at `p` (central differences over one post). */
    glm::dvec3 normalAt(const glm::dvec2& p) const;
};

/**
 * @brief Give every NaN height the height (and normal) of the nearest finite post in grid steps
 * (breadth-first from all finite posts). False when there is no finite post. `queue` is scratch.
 */
bool fillFromNearest(std::vector<float>& heights, std::vector<glm::vec3>& normals, int width,
                     int height, std::vector<std::uint32_t>& queue);

/** @brief Fill `amplitude` from `heights` and `cap` (see kDetailRoughnessGain). */
void computeDetailAmplitude(DetailSketch& sketch);

/**
 * @brief The square region near the camera that the warped grid covers: centred ahead of the
 * camera's nadir, half-size kRangeFactor times the eye's height above `groundZ`, clamped to
 * [4, 128] post spacings and snapped to the post lattice (origin `latticeOrigin`) so the sketch
 * map's posts are the data's posts and the region does not swim as the camera moves.
 */
struct DetailRegion {
    glm::dvec2 min{0.0}, max{0.0};
    bool valid() const { return max.x > min.x && max.y > min.y; }
};
DetailRegion planDetailRegion(const math::Camera& camera, double groundZ, double postSpacing,
                              const glm::dvec2& latticeOrigin, const glm::dvec2& dataMin,
                              const glm::dvec2& dataMax, double rangeScale = 1.0);

/**
 * @brief The largest distance between neighbouring samples of `grid` (metres) among samples on
 * `sketch`'s surface that `camera` sees (inside its frustum): where the grid must be at least
 * as dense as the data's posts.
 */
double maxVisibleGridSpacing(const WarpGrid& grid, const DetailSketch& sketch,
                             const math::Camera& camera);

/**
 * @brief DS04 §3.1's importance over the sketch: I = min(I_v S_f S_b, I_s) with
 *  - I_v = focal / (cellPx * distance): samples per metre for cells of cellPx pixels face-on;
 *  - S_f: 1 inside the view frustum, falling smoothly to a floor outside it;
 *  - S_b: 1 for front-facing and silhouette surface, lower for back-facing slopes;
 *  - I_s: the surface bound: 1 / d0 where the procedural detail is too small to show, up to
 *    2^k / d0 for the finest octave k whose amplitude still projects to half a pixel.
 * A floor (10 % of the maximum; 20 % where visible) and smoothImportance(8) keep the warped
 * grid from folding and visible cells within one post spacing.
 * `size` lattice points per side.
 */
ImportanceMap viewImportance(const DetailSketch& sketch, const math::Camera& camera, double cellPx,
                             int size);

}  // namespace kiosk::terrain
