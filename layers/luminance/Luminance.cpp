#include "layers/luminance/Luminance.h"

namespace kiosk::layers {

std::shared_ptr<const LayerShader> LuminanceKind::shader(const SourcePlan&) const {
    // L * 2 around 0.5: with Modulate, grey 0.5 leaves the colour below unchanged.
    static const auto piece =
        std::make_shared<ExpressionShader>("vec4(vec3(2.0 * $T.r), 1.0)", false);
    return piece;
}

}  // namespace kiosk::layers
