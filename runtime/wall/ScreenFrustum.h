#pragma once

#include "runtime/math/Camera.h"
#include "runtime/wall/Wall.h"

// Off-axis frusta for the screens of a wall (pure; no GL). The virtual camera's vertical field
// of view spans the wall's canvas height (bezels included); its eye sits on the canvas centre's
// normal at the distance that makes this so. Each screen sees the part of that picture behind
// its active area: the generalized perspective projection (Kooima 2008) over the screen's
// corners, so bezels hide the picture like window frames and angled screens stay correct.
namespace kiosk::wall {

/** @brief One screen's view relative to the virtual camera. */
struct ScreenView {
    /** @brief Screen basis in the virtual camera's view space: right, up, normal (to the eye). */
    glm::dvec3 right{1, 0, 0};
    glm::dvec3 up{0, 1, 0};
    glm::dvec3 normal{0, 0, 1};
    math::ImageWindow window;  ///< image-plane extents in the screen's own basis (tangent units)
};

/** @brief Eye distance in mm from the canvas for a vertical field of view `fovYDeg`. */
double eyeDistanceMm(const Wall& wall, double fovYDeg);

/** @brief Screen `index`'s off-axis view for a virtual camera of vertical fov `fovYDeg`. */
ScreenView screenView(const Wall& wall, int index, double fovYDeg);

/**
 * @brief The camera that renders screen `index`: the virtual camera's eye, turned to the
 * screen's basis, with the off-axis window and the screen's pixel size. fovYDeg/aspect are set
 * to the window's equivalent extents (for consumers that think in angles); clip planes are kept
 * (refit them with the scene bounds for angled screens).
 */
math::Camera screenCamera(const math::Camera& virtualCamera, const Wall& wall, int index);

/** @brief The canvas size in pixels at the pixel pitch of screen `index` (rounded). */
glm::ivec2 canvasPixels(const Wall& wall, int index = 0);

}  // namespace kiosk::wall
