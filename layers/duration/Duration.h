#pragma once

#include "layers/Kind.h"

namespace kiosk::layers {

/**
 * @brief Duration above a threshold: the time the sequence's (linearly interpolated) value has
 * spent at or above `product.threshold` up to the data time, in the product's time unit.
 * docs/products.md.
 */
class DurationKind : public Kind {
public:
    std::string plan(const config::Layer& layer, const StoreView& store,
                     SourcePlan& out) const override;
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
    std::string legendTitle(const config::Layer& layer, const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
