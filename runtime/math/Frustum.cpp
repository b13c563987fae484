#include "runtime/math/Frustum.h"

#include <cmath>

namespace kiosk::math {

double Aabb::distanceTo(const glm::dvec3& p) const {
    const glm::dvec3 d = glm::max(glm::max(min - p, glm::dvec3(0.0)), p - max);
    return glm::length(d);
}

Frustum::Frustum(const glm::dmat4& m) {
    // Gribb/Hartmann: rows of the combined matrix (GLM is column-major: m[col][row]).
    auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
    mPlanes[0] = row(3) + row(0);
    mPlanes[1] = row(3) - row(0);
    mPlanes[2] = row(3) + row(1);
    mPlanes[3] = row(3) - row(1);
    mPlanes[4] = row(3) + row(2);
    mPlanes[5] = row(3) - row(2);
    for (auto& p : mPlanes) p /= glm::length(glm::dvec3(p));
}

bool Frustum::intersects(const Aabb& box) const {
    for (const auto& p : mPlanes) {
        // The box corner furthest along the plane normal.
        glm::dvec3 v(p.x >= 0 ? box.max.x : box.min.x, p.y >= 0 ? box.max.y : box.min.y,
                     p.z >= 0 ? box.max.z : box.min.z);
        if (glm::dot(glm::dvec3(p), v) + p.w < 0) return false;
    }
    return true;
}

}  // namespace kiosk::math
