#pragma once

#include <ostream>

namespace kiosk::layers {

/**
 * @brief What a layer kind contributes to the ONE generated compositor pass
 * (render/LayerStack.h): GLSL text only, no GL calls, so it is unit-testable on the text.
 *
 * The compositor owns everything common: it declares `uLayer<i>`, `uLayerRect<i>`,
 * `uLayerParam<i>` (and `uLayerB<i>` / `uLayerT<i>`, `uLayerRectT<i>` for the extra textures
 * a kind asks for), defines `vec2 uv<i>` before calling sample(), binds the texture units, and
 * applies the layer's operation (over / blend / add / modulate / mask) and the lenses to the
 * `vec4 L<i>` the kind defines. A kind never sees the other layers.
 */
class LayerShader {
public:
    virtual ~LayerShader() = default;
    /**
     * @brief Texture units the layer samples, in this order: 1 = uLayer<i>; 2 = + uLayerB<i>
     * (the second frame of a pair); 3 = + uLayerT<i> placed by uLayerRectT<i> (per-pixel
     * thresholds of the pair).
     */
    virtual int textures() const { return 1; }
    /** @brief Coloured through a transfer-function LUT (uLut<k>, k = rank among such layers). */
    virtual bool usesLut() const { return false; }
    /**
     * @brief GLSL functions emitted once per program however many layers of the kind there
     * are (deduplicated by pointer); nullptr for none.
     */
    virtual const char* helpers() const { return nullptr; }
    /**
     * @brief Statements defining `vec4 L<i>` from the layer's samplers at `uv<i>`. `lut` is the
     * layer's LUT index, or -1 when it has none (the layer then stays transparent).
     */
    virtual void sample(std::ostream& s, int i, int lut) const = 0;
    /**
     * @brief Layers of the stack this one is computed from (a difference: 2); the compositor
     * samples them first and calls sampleFrom() with their indices instead of sample().
     */
    virtual int operands() const { return 0; }
    /**
     * @brief sample() for a kind with operands: `operand[k]` is the stack index of operand k,
     * whose statements (e.g. `vec2 d<j>` of scalar kinds) are already emitted; -1 when that
     * layer is not in the stack (failed or disabled): the kind then draws nothing.
     */
    virtual void sampleFrom(std::ostream& s, int i, int lut, const int* operand) const {
        (void)operand;
        sample(s, i, lut);
    }
    /** @brief Only a mask for other layers' Blend: with operation Over it draws nothing. */
    virtual bool maskOnly() const { return false; }
    /**
     * @brief Colours the surface with data (hazard, depth): procedural detail never decorates
     * where such a layer shows (render/ProceduralDetailGlsl.h).
     */
    virtual bool coloursData() const { return false; }
    /**
     * @brief Reads `uniform vec4 uLayerProduct<i>` = (time of the pair's first frame, the
     * pair's interval) in the product's time unit (derived products, layers/products/).
     */
    virtual bool productUniform() const { return false; }
};

}  // namespace kiosk::layers
