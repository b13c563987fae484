#include "runtime/math/Camera.h"

#include <algorithm>
#include <cmath>

namespace kiosk::math {

Camera Camera::fromViewpoint(const Viewpoint& vp, int viewportWidth, int viewportHeight,
                             double fovYDeg) {
    Camera c;
    const double h = glm::radians(vp.headingDeg);
    const double p = glm::radians(std::clamp(vp.pitchDeg, -89.9, 89.9));
    // Direction the camera looks: heading clockwise from north (+y), pitch below horizon < 0.
    c.forward = glm::dvec3(std::sin(h) * std::cos(p), std::cos(h) * std::cos(p), std::sin(p));
    c.eye = vp.target - c.forward * vp.range;
    const glm::dvec3 right = glm::normalize(glm::cross(c.forward, glm::dvec3(0.0, 0.0, 1.0)));
    c.up = glm::normalize(glm::cross(right, c.forward));
    c.fovYDeg = fovYDeg;
    c.viewportWidth = viewportWidth;
    c.viewportHeight = viewportHeight;
    c.aspect = double(viewportWidth) / double(std::max(1, viewportHeight));
    c.nearPlane = std::max(1.0, vp.range * 0.01);
    c.farPlane = vp.range * 20.0;
    return c;
}

glm::dmat4 Camera::view(const glm::dvec3& origin) const {
    return glm::lookAt(eye - origin, eye - origin + forward, up);
}

glm::dmat4 Camera::projection() const {
    if (window)
        return glm::frustum(window->left * nearPlane, window->right * nearPlane,
                            window->bottom * nearPlane, window->top * nearPlane, nearPlane,
                            farPlane);
    return glm::perspective(glm::radians(fovYDeg), aspect, nearPlane, farPlane);
}

double Camera::pixelsPerMetreAt(double distance) const {
    const double d = std::max(distance, 1e-6);
    if (window) return double(viewportHeight) / ((window->top - window->bottom) * d);
    return double(viewportHeight) / (2.0 * std::tan(glm::radians(fovYDeg) * 0.5) * d);
}

void Camera::fitClipPlanes(const glm::dvec3& bmin, const glm::dvec3& bmax) {
    double nearest = 1e300, farthest = 0.0;
    for (int i = 0; i < 8; ++i) {
        glm::dvec3 corner((i & 1) ? bmax.x : bmin.x, (i & 2) ? bmax.y : bmin.y,
                          (i & 4) ? bmax.z : bmin.z);
        double d = glm::dot(corner - eye, forward);
        nearest = std::min(nearest, d);
        farthest = std::max(farthest, d);
    }
    farPlane = std::max(farthest * 1.05, 10.0);
    // Keep the depth range ratio bounded (24-bit depth); the nearest terrain may be behind us.
    nearPlane = std::clamp(nearest * 0.9, farPlane / 20000.0, farPlane * 0.5);
}

}  // namespace kiosk::math
