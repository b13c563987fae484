#pragma once

#include "layers/ImageryKind.h"

namespace kiosk::layers {

/**
 * @brief Dynamic light from a normal-map layer (Döllner §7.4) and hybrid shading (Baumann): the
 * store's normal map (docs/store-format.md "Normal maps") lit by the run-time sun, blended to
 * the mesh's own shading where its texels are magnified past tauTex. The C++ mirror of the
 * blend weight is render::hybridGeometryWeight (runtime/render/NormalShading.h).
 *
 * Reads besides the layer's own uniforms: uLightDir, uAmbient, uVerticalScale (compositor
 * prelude) and uTauTex (declared by its helpers, set from TerrainStyle::tauTex).
 */
class NormalsKind : public ImageryKind {
public:
    std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const override;
};

}  // namespace kiosk::layers
