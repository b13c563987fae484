#pragma once

#include "layers/Kind.h"

namespace kiosk::layers {

/**
 * @brief A - B of two scalar layers of the stack (`"of": [A, B]`, sequences or data layers,
 * e.g. two model runs from two stores, or forecast and observed) at the same data time, each
 * interpolated as its own layer draws it, coloured through the layer's (diverging) transfer
 * function. Loads nothing itself: the scene serves A and B as the layers they are, so the
 * difference steps exactly when they do. Valid where both are valid; elsewhere the transfer
 * function's nodata colour.
 */
class DifferenceKind : public Kind {
public:
    std::string plan(const config::Layer& layer, const StoreView& store,
                     SourcePlan& out) const override;
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
    /** @brief "Difference A - B" (the operands' layer ids): the legend of a diverging function. */
    std::string legendTitle(const config::Layer& layer, const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
