#pragma once

#include "layers/ImageryKind.h"

namespace kiosk::layers {

/** @brief An alpha mask: no colour of its own, the source of other layers' Blend and of Mask. */
class VisibilityKind : public ImageryKind {
public:
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
