#pragma once

#include "layers/Kind.h"

#include <ostream>

namespace kiosk::layers {

/**
 * @brief What the scalar kinds (data, sequence, and products derived from sequences) share:
 * a store sequence as the source and colour through the layer's transfer-function LUT.
 */
struct ScalarSource {
    /** @brief The layer's sequence (source.sequence) with its levels; the reason if absent. */
    static std::string plan(const config::Layer& layer, const StoreView& store, SourcePlan& out);
    /**
     * @brief With `vec2 d<i>` = (value x validity, validity) defined: `vec4 L<i>` from LUT `lut`
     * (transparent when lut < 0). Values are premultiplied by validity so filtering then
     * dividing gives the mean of valid neighbours: nodata never bleeds into values.
     */
    static void appendColour(std::ostream& s, int i, int lut);
};

}  // namespace kiosk::layers
