#pragma once

#include "layers/Kind.h"

namespace kiosk::layers {

/**
 * @brief Base of the kinds drawn from one RGBA raster layer of the store (thematic, luminance,
 * topographic, normals, visibility): they differ only in their GLSL.
 */
class ImageryKind : public Kind {
public:
    std::string plan(const config::Layer& layer, const StoreView& store,
                     SourcePlan& out) const override;
};

/** @brief A LayerShader whose sample() is one statement `vec4 L<i> = <expr>;` */
class ExpressionShader : public LayerShader {
public:
    /** @brief `expr` with `$T` for `texture(uLayer<i>, uv<i>)`. */
    ExpressionShader(const char* expr, bool maskOnly) : mExpr(expr), mMaskOnly(maskOnly) {}
    void sample(std::ostream& s, int i, int lut) const override;
    bool maskOnly() const override { return mMaskOnly; }

private:
    const char* mExpr;
    bool mMaskOnly;
};

}  // namespace kiosk::layers
