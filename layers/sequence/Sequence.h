#pragma once

#include "layers/Kind.h"

namespace kiosk::layers {

/**
 * @brief A time-keyed sequence: the two frames bracketing the data time, interpolated in DATA
 * space and then coloured (never two colours blended). Class data switches without blending;
 * `interpolate: "arrival"` adds per-pixel thresholds of the pair (computed by the loader) so a
 * front sweeps across between the steps.
 */
class SequenceKind : public Kind {
public:
    std::string plan(const config::Layer& layer, const StoreView& store,
                     SourcePlan& out) const override;
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
