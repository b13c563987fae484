#pragma once

#include <array>

#include "runtime/math/Glm.h"

namespace kiosk::math {

/** @brief Axis-aligned box in world coordinates (double). */
struct Aabb {
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
    glm::dvec3 center() const { return (min + max) * 0.5; }
    /** @brief Euclidean distance from p to the box (0 inside). */
    double distanceTo(const glm::dvec3& p) const;
};

/** @brief Six planes (a·x + d >= 0 inside) extracted from a view-projection matrix. */
class Frustum {
public:
    Frustum() = default;
    explicit Frustum(const glm::dmat4& viewProjection);
    /** @brief False only if the box is entirely outside one plane (conservative). */
    bool intersects(const Aabb& box) const;

private:
    std::array<glm::dvec4, 6> mPlanes{};
};

}  // namespace kiosk::math
