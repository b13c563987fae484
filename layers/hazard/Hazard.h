#pragma once

#include "layers/Kind.h"

namespace kiosk::layers {

/**
 * @brief Flood hazard class H1..H6 (Australian Rainfall and Runoff 2019, Book 6 Chapter 7) from
 * the depth sequence and `product.velocity` (a velocity sequence of the same store), derived
 * per step on the loader thread; from depth alone when the data has no velocity (the legend
 * says so). Shown at the step at or before the data time (classes never blend).
 */
class HazardKind : public Kind {
public:
    std::string plan(const config::Layer& layer, const StoreView& store,
                     SourcePlan& out) const override;
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
    std::string legendTitle(const config::Layer& layer, const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
