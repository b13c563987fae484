#pragma once

#include "layers/Kind.h"

namespace kiosk::layers {

/**
 * @brief A scalar raster coloured by a transfer function: one frame of a store sequence (the
 * raw step at or before the data time), or the terrain's own elevation when its source layer is
 * the elevation layer (hypsometric tint without a texture).
 */
class DataKind : public Kind {
public:
    std::string plan(const config::Layer& layer, const StoreView& store,
                     SourcePlan& out) const override;
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
