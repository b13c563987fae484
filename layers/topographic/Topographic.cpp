#include "layers/topographic/Topographic.h"

namespace kiosk::layers {

std::shared_ptr<const LayerShader> TopographicKind::shader(const SourcePlan&) const {
    // The grey shading in rgb, its own alpha (nodata) kept.
    static const auto piece = std::make_shared<ExpressionShader>("$T.rrra", false);
    return piece;
}

}  // namespace kiosk::layers
