#pragma once

namespace kiosk::render {

// The normals kind's GLSL (decoding, Lambert with the run-time sun, the hybrid switch to
// geometry shading past tauTex) is in layers/normals/Normals.cpp; this is its C++ mirror.

/**
 * @brief Weight of geometry shading in the hybrid blend (C++ mirror of the GLSL): 0 while a
 * texel covers at most tauTex screen pixels, 1 from 2 * tauTex pixels on, smoothstep of
 * log2(pixelsPerTexel / tauTex) in between (one octave of camera distance). tauTex <= 0 or
 * non-finite input gives 0 (texture shading only).
 */
float hybridGeometryWeight(float pixelsPerTexel, float tauTex);

}  // namespace kiosk::render
