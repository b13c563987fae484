#pragma once

#include "runtime/mapping/MappingModel.h"

#include <cstdint>
#include <vector>

namespace kiosk::mapping {

/** @brief Which procedural texture a route piece samples. */
enum class RoutePieceKind { Edge, Point };

struct RoutePiece {
    RoutePieceKind kind = RoutePieceKind::Edge;
    MappingState state;
};

/**
 * @brief The paper's way-point and edge mappings (§5.1) on the horizontal reference plane:
 * for way points W_0..W_n, one edge mapping per segment with O = (W_s + W_e) / 2, U along the
 * segment (its length plus `width`, so consecutive edges overlap at bends) and V = N × Û ·
 * `width`; then, when `pointRadius` > 0, one point mapping per way point with O = W_i,
 * U = (2r, 0, 0), V = (0, 2r, 0). Edges come first so points draw over them. Colour matrix,
 * opacity and enabled come from `base`; zero-length segments are skipped. Pure; any thread.
 */
std::vector<RoutePiece> routeMappings(const MappingState& base,
                                      const std::vector<glm::dvec2>& points, double width,
                                      double pointRadius);

/**
 * @brief Edge texture: a line profile across t (white, alpha 1 in the middle 60 %, smooth
 * falloff to 0 at t = 0 and 1), constant along s. RGBA8, `size` x `size`, top row first.
 */
std::vector<std::uint8_t> edgeProfileImage(int size);

/** @brief Point texture: a white disc, alpha 1 inside radius 0.4, 0 beyond 0.5 (of the side). */
std::vector<std::uint8_t> discImage(int size);

}  // namespace kiosk::mapping
