#include "runtime/wall/ScreenFrustum.h"

#include <cmath>

namespace kiosk::wall {

double eyeDistanceMm(const Wall& wall, double fovYDeg) {
    return wall.canvasMmY * 0.5 / std::tan(glm::radians(fovYDeg) * 0.5);
}

ScreenView screenView(const Wall& wall, int index, double fovYDeg) {
    const Screen& s = wall.screens[std::size_t(index)];
    const double d = eyeDistanceMm(wall, fovYDeg);
    // Wall plane at z = -d in the virtual camera's view space (x right, y up); wall mm have y down.
    const glm::dvec3 centre(s.xMm + s.activeMmX * 0.5 - wall.canvasMmX * 0.5,
                            wall.canvasMmY * 0.5 - (s.yMm + s.activeMmY * 0.5), -d);
    // Angled screens turn about their own centre: yaw about up, then pitch, then roll.
    glm::dmat4 rot(1.0);
    rot = glm::rotate(rot, glm::radians(s.yawDeg), glm::dvec3(0, 1, 0));
    rot = glm::rotate(rot, glm::radians(-s.pitchDeg), glm::dvec3(1, 0, 0));
    rot = glm::rotate(rot, glm::radians(s.rollDeg), glm::dvec3(0, 0, 1));
    const glm::dmat3 r(rot);
    const double hw = s.activeMmX * 0.5, hh = s.activeMmY * 0.5;
    const glm::dvec3 pa = centre + r * glm::dvec3(-hw, -hh, 0);  // lower left
    const glm::dvec3 pb = centre + r * glm::dvec3(hw, -hh, 0);   // lower right
    const glm::dvec3 pc = centre + r * glm::dvec3(-hw, hh, 0);   // upper left
    ScreenView v;
    v.right = glm::normalize(pb - pa);
    v.up = glm::normalize(pc - pa);
    v.normal = glm::normalize(glm::cross(v.right, v.up));
    // Eye at the origin: distance to the screen plane and the corners in the screen's basis.
    const double dist = -glm::dot(v.normal, pa);
    v.window.left = glm::dot(v.right, pa) / dist;
    v.window.right = glm::dot(v.right, pb) / dist;
    v.window.bottom = glm::dot(v.up, pa) / dist;
    v.window.top = glm::dot(v.up, pc) / dist;
    return v;
}

math::Camera screenCamera(const math::Camera& vc, const Wall& wall, int index) {
    const ScreenView v = screenView(wall, index, vc.fovYDeg);
    const glm::dvec3 f = glm::normalize(vc.forward);
    const glm::dvec3 rightW = glm::normalize(glm::cross(f, vc.up));
    const glm::dvec3 upW = glm::cross(rightW, f);
    auto toWorld = [&](const glm::dvec3& a) { return rightW * a.x + upW * a.y - f * a.z; };
    math::Camera c = vc;
    c.forward = glm::normalize(toWorld(-v.normal));
    c.up = glm::normalize(toWorld(v.up));
    c.window = v.window;
    const Screen& s = wall.screens[std::size_t(index)];
    c.viewportWidth = s.pixelsX;
    c.viewportHeight = s.pixelsY;
    const double h = v.window.top - v.window.bottom;
    c.fovYDeg = glm::degrees(2.0 * std::atan(h * 0.5));
    c.aspect = (v.window.right - v.window.left) / h;
    return c;
}

glm::ivec2 canvasPixels(const Wall& wall, int index) {
    const Screen& s = wall.screens[std::size_t(index)];
    return {int(std::lround(wall.canvasMmX * s.pixelsX / s.activeMmX)),
            int(std::lround(wall.canvasMmY * s.pixelsY / s.activeMmY))};
}

}  // namespace kiosk::wall
