#include "runtime/app/LensControl.h"

#include <cmath>

namespace kiosk::app {

bool applyLensMove(scene::TerrainScene& scene, const service::LensMove& move, std::string& why) {
    const int index = move.id.empty() ? scene.primaryLens() : scene.lensIndex(move.id);
    if (index < 0) {
        why = move.id.empty() ? "the scenario has no lens" : "no lens \"" + move.id + "\"";
        return false;
    }
    scene::LensPlacement p = *scene.lensPlacement(index);
    if (move.x) p.centre.x = *move.x;
    if (move.y) p.centre.y = *move.y;
    if (move.radius)  // a circle gets the radius; an ellipse its larger radius, same aspect
        p.radii *= *move.radius / std::max(p.radii.x, p.radii.y);
    if (move.rotation) p.rotationDeg = *move.rotation;
    if (move.enabled) p.enabled = *move.enabled;
    return scene.placeLens(index, p);
}

void applyLensKeys(scene::TerrainScene& scene, const platform::InputState& input) {
    if (!input.lensX && !input.lensY && !input.lensSize && !input.lensTurn && !input.lensToggle)
        return;
    const int index = scene.primaryLens();
    if (index < 0) return;
    scene::LensPlacement p = *scene.lensPlacement(index);
    const math::Aabb& b = scene.bounds();
    const double step = std::max(b.max.x - b.min.x, b.max.y - b.min.y) / 20.0;
    p.centre += step * glm::dvec2(input.lensX, input.lensY);
    p.radii *= std::pow(1.1, input.lensSize);
    p.rotationDeg = std::fmod(p.rotationDeg + 15.0 * input.lensTurn, 360.0);
    if (input.lensToggle) p.enabled = !p.enabled;
    scene.placeLens(index, p);
}

}  // namespace kiosk::app
