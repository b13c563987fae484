#include "layers/thematic/Thematic.h"

namespace kiosk::layers {

std::shared_ptr<const LayerShader> ThematicKind::shader(const SourcePlan&) const {
    // The texel as it is; the operation decides how it covers what is below.
    static const auto piece = std::make_shared<ExpressionShader>("$T", false);
    return piece;
}

}  // namespace kiosk::layers
