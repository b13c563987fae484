#include "runtime/mapping/MappingCuller.h"

#include <algorithm>
#include <cmath>

namespace kiosk::mapping {

void MappingCounts::add(CullResult r) {
    switch (r) {
        case CullResult::Active:
            ++active;
            break;
        case CullResult::Frustum:
            ++culledFrustum;
            break;
        case CullResult::Size:
            ++culledSize;
            break;
        case CullResult::Disabled:
        case CullResult::Degenerate:
            ++disabled;
            break;
    }
}

math::Aabb footprint(const MappingState& s, double zMin, double zMax, double reach) {
    const glm::dvec3 n = glm::cross(s.u, s.v);
    const double nl = glm::length(n);
    const glm::dvec3 nHat = nl > 0.0 ? n / nl : glm::dvec3(0.0, 0.0, 1.0);
    math::Aabb box{glm::dvec3(1e300), glm::dvec3(-1e300)};
    for (double a : {-0.5, 0.5})
        for (double b : {-0.5, 0.5}) {
            const glm::dvec3 c = s.origin + a * s.u + b * s.v;
            box.min = glm::min(box.min, c);
            box.max = glm::max(box.max, c);
        }
    if (std::abs(nHat.z) >= 0.1) {
        // Near-horizontal plane: the sweep along N reaches every terrain height; the
        // horizontal drift over that height is bounded by the slant of N.
        const double dz = std::max(std::abs(zMax - box.min.z), std::abs(box.max.z - zMin));
        const double drift = dz * glm::length(glm::dvec2(nHat)) / std::abs(nHat.z);
        box.min = glm::dvec3(box.min.x - drift, box.min.y - drift, std::min(box.min.z, zMin));
        box.max = glm::dvec3(box.max.x + drift, box.max.y + drift, std::max(box.max.z, zMax));
    } else {
        const glm::dvec3 r = glm::abs(nHat) * reach;
        box.min -= r;
        box.max += r;
    }
    return box;
}

double screenSizeRho(const MappingState& s, const math::Camera& camera, double sceneScale) {
    const double scale = std::max(sceneScale, 1e-9);
    const double hfovRad =
        2.0 * std::atan(std::tan(glm::radians(camera.fovYDeg) * 0.5) * camera.aspect);
    const double phiDeg = glm::degrees(hfovRad);
    const double dist = std::max(glm::length(s.origin - camera.eye) / scale, 1e-12);
    const double area = (glm::length(s.u) / scale) * (glm::length(s.v) / scale);
    return double(camera.viewportWidth) / phiDeg * area / dist;
}

CullResult cull(const MappingState& s, const math::Camera& camera, const math::Frustum& frustum,
                const CullOptions& o) {
    if (!s.enabled || s.opacity <= 0.0) return CullResult::Disabled;
    if (!(glm::length(glm::cross(s.u, s.v)) > 0.0)) return CullResult::Degenerate;
    const double reach = 4.0 * std::max(o.sceneScale, glm::length(s.u) + glm::length(s.v));
    if (!frustum.intersects(footprint(s, o.zMin, o.zMax, reach))) return CullResult::Frustum;
    if (screenSizeRho(s, camera, o.sceneScale) < o.sizeThreshold) return CullResult::Size;
    return CullResult::Active;
}

}  // namespace kiosk::mapping
