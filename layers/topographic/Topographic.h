#pragma once

#include "layers/ImageryKind.h"

namespace kiosk::layers {

/** @brief A shading texture (hillshade) that modulates what is below. */
class TopographicKind : public ImageryKind {
public:
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
