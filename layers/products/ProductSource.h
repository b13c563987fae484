#pragma once

#include "layers/Kind.h"

#include <ostream>

namespace kiosk::layers::products {

/**
 * @brief What the cumulative product kinds share: one tile per frame k of the layer's sequence,
 * derived on the loader thread (state after frame k + the frames k and k + 1, one RGBA16F
 * texel, products::Cumulative), served and committed atomically like a sequence's frames; the
 * time axis; and the GLSL reading the texel.
 */
struct ProductSource {
    /** @brief Plan the product tiles of the sequence; the reason if it cannot be served. */
    static std::string plan(const config::Layer& layer, const StoreView& store, SourcePlan& out);
    /**
     * @brief Statements reading layer i's product texel: `bool sv<i>` (the state has a value),
     * `float S<i>` (the state after the pair's first frame), `v0_<i>`, `v1_<i>` (the two frames
     * on screen), `al<i>` (the blend factor), `bool cv<i>` (both frames hold data) and
     * `cur<i>` (the value on screen, interpolated in data space as a sequence layer).
     */
    static void sampleProduct(std::ostream& s, int i);
    /** @brief "depth >= 0.1 m": the sequence's variable, the threshold and its units. */
    static std::string thresholdText(const config::Layer& layer, const SourcePlan& plan);
    /** @brief The sequence's variable ("depth"), or its name when the store records none. */
    static std::string variable(const SourcePlan& plan);
    /** @brief A GLSL float literal of `v` (GLSL ES never converts int literals). */
    static std::string literal(double v);
    /**
     * @brief `product` (maximum, arrival or duration) carries the frame pair `sequence` draws:
     * same store, sequence and nodataAs, values interpolated as data. The sequence layer then
     * reads its value from the product's texel (sequenceFromProduct()) instead of its own two
     * frame textures: one frame-pair read for both.
     */
    static bool carriesFramesOf(const config::Layer& product, const config::Layer& sequence,
                                const std::string& terrainStore);
    /** @brief The sequence layer's piece then: its operand is the product layer. */
    static std::shared_ptr<const LayerShader> sequenceFromProduct();
};

}  // namespace kiosk::layers::products
