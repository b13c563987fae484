#pragma once

#include "layers/ImageryKind.h"

namespace kiosk::layers {

/** @brief A grey texture that brightens or darkens what is below (0.5 = neutral). */
class LuminanceKind : public ImageryKind {
public:
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
