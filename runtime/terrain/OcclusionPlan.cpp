#include "runtime/terrain/OcclusionPlan.h"

#include <algorithm>
#include <cmath>

namespace kiosk::terrain {

std::vector<std::size_t> OcclusionPlan::roundStarts(std::size_t tiles) {
    std::vector<std::size_t> starts;
    if (tiles < kMinTiles) return starts;
    // The first quarter (the nearest tiles) is drawn untested; the rest in equal batches, so
    // later batches are tested against everything nearer that survived the earlier ones.
    for (int r = 1; r <= kRounds; ++r) {
        const std::size_t s = tiles * std::size_t(r) / std::size_t(kRounds + 1);
        if (starts.empty() || s > starts.back()) starts.push_back(s);
    }
    return starts;
}

std::optional<math::Aabb> OcclusionPlan::queryBox(const math::Camera& camera,
                                                  const math::Aabb& tight, double minMargin) {
    // Farthest view-space depth of the box: the margins grow with distance.
    const glm::dvec3 f = glm::normalize(camera.forward);
    double farDepth = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p((c & 1) ? tight.max.x : tight.min.x, (c & 2) ? tight.max.y : tight.min.y,
                           (c & 4) ? tight.max.z : tight.min.z);
        farDepth = std::max(farDepth, glm::dot(p - camera.eye, f));
    }
    const double nearPlane = std::max(camera.nearPlane, 1e-6);
    const double depthStep = farDepth * farDepth / nearPlane * std::ldexp(1.0, -24);
    const double halfPixel = farDepth > 0 ? 0.5 / camera.pixelsPerMetreAt(farDepth) : 0.0;
    const double margin = std::max({minMargin, 0.0, halfPixel, 8.0 * depthStep});
    math::Aabb box{tight.min - glm::dvec3(margin), tight.max + glm::dvec3(margin)};
    // Every corner must be beyond the near plane (with a relative slack for the projection's
    // float rounding); otherwise the clipped box has no front face in front of the tile.
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                           (c & 4) ? box.max.z : box.min.z);
        if (glm::dot(p - camera.eye, f) <= nearPlane * 1.001) return std::nullopt;
    }
    return box;
}

}  // namespace kiosk::terrain
