#pragma once

#include "layers/ImageryKind.h"

namespace kiosk::layers {

/** @brief An RGBA image (imagery, land use) applied by its operation (Döllner 2000, §3). */
class ThematicKind : public ImageryKind {
public:
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
