#pragma once

#include "layers/Kind.h"

#include <ostream>

namespace kiosk::layers::products {

/**
 * @brief What the product kinds share: the layer's sequence as the frame pair (interpolated in
 * data space as a sequence layer), a cumulative state from the loader at the pair's first frame
 * (uLayerT), the time axis, and GLSL to read the three textures.
 */
struct ProductSource {
    /** @brief Plan the sequence pair; the reason if it cannot be served. */
    static std::string plan(const config::Layer& layer, const StoreView& store, SourcePlan& out);
    /** @brief GLSL helpers shared by every product (one pointer: emitted once per program). */
    static const char* helpers();
    /**
     * @brief Statements defining `vec2 a<i>`, `b<i>` (the pair, (value x valid, valid)),
     * `s<i>` (the state at the first frame) and `float al<i>` (the pair's blend factor).
     */
    static void samplePair(std::ostream& s, int i);
    /** @brief "depth >= 0.1 m": the sequence's variable, the threshold and its units. */
    static std::string thresholdText(const config::Layer& layer, const SourcePlan& plan);
    /** @brief The sequence's variable ("depth"), or its name when the store records none. */
    static std::string variable(const SourcePlan& plan);
    /** @brief A GLSL float literal of `v` (GLSL ES never converts int literals). */
    static std::string literal(double v);
};

}  // namespace kiosk::layers::products
