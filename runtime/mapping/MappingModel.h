#pragma once

#include "config/Scenario.h"
#include "runtime/math/Glm.h"

#include <optional>

namespace kiosk::mapping {

/**
 * @brief One projective mapping's geometry and colour parameters at a point in time
 * (Trapp & Döllner, PM = (O, U, V, M_T, L_i, C_j, CM)). All positions are store CRS metres.
 * The rectangle is O ± U/2 ± V/2; texture s runs along U, t along V, (0.5, 0.5) at O. An image's
 * top row lies at the +V edge.
 */
struct MappingState {
    glm::dvec3 origin{0.0};
    glm::dvec3 u{1.0, 0.0, 0.0};
    glm::dvec3 v{0.0, 1.0, 0.0};
    glm::dmat3 textureMatrix{1.0};  ///< M_T, applied to (s, t, 1)
    glm::dmat4 colorMatrix{1.0};    ///< M_C, applied to (r, g, b, 1); alpha untouched
    double opacity = 1.0;
    bool enabled = true;
};

/** @brief Row-major scenario matrices into glm (column-major). */
glm::dmat3 toGlm(const config::Mat3& m);
glm::dmat4 toGlm(const config::Mat4& m);

/**
 * @brief The mapping's parameters at `time` (epoch seconds; keys resolved against
 * `clockStart`). Same rule as the lenses: the first key holds before its time, piecewise
 * linear between keys, hold the last key after it. Axes u and v interpolate direction and length
 * separately, so a keyed rotation keeps the symbol's size. Keys missing a field keep the value
 * reached so far. Pure; any thread.
 */
MappingState evaluate(const config::ProjectiveMapping& mapping, double time, double clockStart);

/**
 * @brief T = M_T · M_P · M_O of the paper (§3.1), kept in two steps for points given relative
 * to `sceneOrigin`. First the rectangle coordinate r = (rowS · (x, y, z, 1), rowT · (...)):
 * the point in the (U, V, N) basis around O (N = U × V, the orthographic direction of
 * projection; non-orthogonal U and V through the dual basis), shifted so O is (0.5, 0.5) and
 * the rectangle is [0,1]². Then the sampling coordinate M_T · (r, 1), divided by its w.
 * testAABB2D is applied to r, so the footprint is always the rectangle (the region the CPU
 * culls) and M_T only moves what is sampled - e.g. one cell of a symbol atlas.
 */
struct TextureTransform {
    glm::dvec4 rowS{0.0}, rowT{0.0};
    glm::dmat3 textureMatrix{1.0};
    /** @brief Rectangle coordinate r of a point relative to the scene origin. */
    glm::dvec2 rect(const glm::dvec3& p) const;
    /** @brief Sampling coordinate M_T · (r, 1) / w. */
    glm::dvec2 apply(const glm::dvec3& p) const;
};

/** @brief Nullopt when U or V is zero or they are parallel (no plane). */
std::optional<TextureTransform> textureTransform(const MappingState& state,
                                                 const glm::dvec3& sceneOrigin);

/** @brief The paper's testAABB2D: both coordinates in [0, 1] (applied to rect()). */
inline bool testAABB2D(const glm::dvec2& s) {
    return s.x >= 0.0 && s.x <= 1.0 && s.y >= 0.0 && s.y <= 1.0;
}

}  // namespace kiosk::mapping
