#pragma once

#include "layers/Kind.h"

namespace kiosk::layers {

/**
 * @brief Maximum so far of a sequence: the envelope of every value up to the data time
 * (the loader's running maximum at the pair's first frame, combined with the value on screen).
 * Over burn-state classes it is the burned area so far (docs/products.md).
 */
class MaximumKind : public Kind {
public:
    std::string plan(const config::Layer& layer, const StoreView& store,
                     SourcePlan& out) const override;
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
    std::string legendTitle(const config::Layer& layer, const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
