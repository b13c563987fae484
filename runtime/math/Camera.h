#pragma once

#include "runtime/math/Glm.h"

#include <optional>

namespace kiosk::math {

/**
 * @brief An orbit view: look at `target` (world CRS metres, z up) from `range` metres away,
 * `headingDeg` clockwise from north, `pitchDeg` below the horizon is negative (-90 = straight down).
 * This is the form scenarios use for viewpoints and camera paths.
 */
struct Viewpoint {
    glm::dvec3 target{0.0};
    double headingDeg = 0.0;
    double pitchDeg = -45.0;
    double range = 1000.0;
};

/**
 * @brief An off-axis image-plane window in tangent units: the view-space rectangle
 * [left, right] x [bottom, top] at unit distance in front of the eye (x right, y up).
 * A symmetric camera is [-tan(fovY/2) aspect, +...] x [-tan(fovY/2), +tan(fovY/2)].
 */
struct ImageWindow {
    double left = -1.0;
    double right = 1.0;
    double bottom = -1.0;
    double top = 1.0;
};

/** @brief A perspective camera in double precision. */
struct Camera {
    glm::dvec3 eye{0.0};
    glm::dvec3 forward{0.0, 1.0, 0.0};
    glm::dvec3 up{0.0, 0.0, 1.0};
    double fovYDeg = 45.0;
    double aspect = 16.0 / 9.0;
    double nearPlane = 1.0;
    double farPlane = 100000.0;
    int viewportWidth = 1280;
    int viewportHeight = 720;
    /**
     * @brief Set for one screen of a display wall: the projection is glm::frustum over this
     * window (asymmetric) instead of the symmetric fovY/aspect one, and the pixel density used
     * by the screen-space error follows the window's height (runtime/wall/ScreenFrustum.h).
     */
    std::optional<ImageWindow> window;

    static Camera fromViewpoint(const Viewpoint& vp, int viewportWidth, int viewportHeight,
                                double fovYDeg = 45.0);

    /** @brief View matrix relative to `origin` (so float precision holds near the camera). */
    glm::dmat4 view(const glm::dvec3& origin = glm::dvec3(0.0)) const;
    glm::dmat4 projection() const;
    /**
     * @brief Pixels per metre of a length seen face-on at `distance` metres:
     * viewportHeight / (2 tan(fovY/2) distance), or viewportHeight / ((top - bottom) distance)
     * with an off-axis window. Screen-space error = error * this.
     */
    double pixelsPerMetreAt(double distance) const;
    /** @brief Near/far planes chosen to bracket a scene of the given world bounds. */
    void fitClipPlanes(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax);
};

}  // namespace kiosk::math
