#pragma once

#include "layers/Kind.h"

namespace kiosk::layers {

/**
 * @brief Arrival time: when the sequence's value first reached `product.threshold`, in the
 * product's time unit since the clock start, interpolated between steps; with
 * `product.isochrones` only lines every that many units (fire isochrones). docs/products.md.
 */
class ArrivalKind : public Kind {
public:
    std::string plan(const config::Layer& layer, const StoreView& store,
                     SourcePlan& out) const override;
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
    std::string legendTitle(const config::Layer& layer, const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
