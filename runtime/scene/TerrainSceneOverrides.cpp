// Per-chapter layer overrides (briefings): a layer of the stack hidden or drawn at another
// opacity without rebuilding the stack. A hidden layer keeps loading (switching chapters back
// shows it at once); it only stops contributing to the composite.
#include "runtime/scene/TerrainScene.h"

namespace kiosk::scene {

bool TerrainScene::setLayerOverride(const std::string& id, bool visible,
                                    std::optional<double> opacity) {
    for (auto& l : mLayers) {
        if (l.config->id != id) continue;
        const auto& op = l.config->operation;
        // Every operation scales its effect by the strength, so 0 leaves the layers below as
        // they are (opacity-over, add, modulate and mask alike).
        const double weight = op.type == config::OperationType::Add ? op.weight : 1.0;
        l.strengthOverride = visible ? float(opacity.value_or(op.opacity) * weight) : 0.0f;
        return true;
    }
    return false;  // not in the stack (failed to load): nothing to override
}

void TerrainScene::clearLayerOverrides() {
    for (auto& l : mLayers) l.strengthOverride.reset();
}

}  // namespace kiosk::scene
