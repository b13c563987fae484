#pragma once

#include <ostream>

namespace kiosk::render {

/**
 * @brief Dynamic light from a normal-map layer (Döllner §7.4) and hybrid shading (Baumann):
 * the GLSL a `LayerKind::Normals` layer adds to the generated composite shader.
 *
 * The layer's texture is the store's normal map (docs/store-format.md "Normal maps"): RGB =
 * Rgb8-encoded unit normal (east, north, up), A = 1 valid / 0 nodata, nodata texels all zero.
 * Because nodata texels are all zero, a filtered texel is a premultiplied mean of its valid
 * neighbours: rgb / a recovers their mean encoded normal, so nodata never shades a rim.
 *
 * Shading of the layer (grey, used by its operation, normally Modulate):
 *   sT = Lambert(decoded normal with xy scaled by the vertical exaggeration, uLightDir, uAmbient)
 *   sG = Lambert(vNormal, uLightDir, uAmbient)  (the mesh's normal, per fragment)
 *   g  = hybridGeometryWeight(screen pixels per texel, uTauTex)
 *   L  = vec4(vec3(mix(sT, sG, g)), a)
 * Pixels per texel come from the derivatives of the texel coordinate (uv * textureSize), so g
 * is continuous over the screen and over camera distance: no seam.
 *
 * Uniforms it reads besides the layer's own: uLightDir, uAmbient (prelude), uVerticalScale
 * (shared with the vertex shader), uTauTex (TerrainStyle::tauTex).
 */
struct NormalShading {
    /** @brief GLSL functions and uniforms, emitted once when a stack has a Normals layer. */
    static const char* glslHelpers();
    /** @brief Statements defining `vec4 L<i>` from uLayer<i> at uv<i>. */
    static void appendLayerSample(std::ostream& s, int i);
};

/**
 * @brief Weight of geometry shading in the hybrid blend (C++ mirror of the GLSL): 0 while a
 * texel covers at most tauTex screen pixels, 1 from 2 * tauTex pixels on, smoothstep of
 * log2(pixelsPerTexel / tauTex) in between (one octave of camera distance). tauTex <= 0 or
 * non-finite input gives 0 (texture shading only).
 */
float hybridGeometryWeight(float pixelsPerTexel, float tauTex);

}  // namespace kiosk::render
