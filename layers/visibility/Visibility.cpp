#include "layers/visibility/Visibility.h"

namespace kiosk::layers {

std::shared_ptr<const LayerShader> VisibilityKind::shader(const SourcePlan&) const {
    // The mask is the red channel; white so a Mask/Blend reads only alpha.
    static const auto piece = std::make_shared<ExpressionShader>("vec4(1.0, 1.0, 1.0, $T.r)", true);
    return piece;
}

}  // namespace kiosk::layers
