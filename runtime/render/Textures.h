#pragma once

#include <cstdint>
#include <optional>

#include "runtime/gl/GlObject.h"

namespace kiosk::render {

/** @brief RGBA8 2D texture from tightly packed pixels (top row first), linear, clamped. */
gl::Texture makeRgbaTexture(int width, int height, const std::uint8_t* rgba, bool mipmaps);

/**
 * @brief A transfer-function LUT as a `size x 1` RGBA8 texture sampled with LINEAR filtering
 * so that any number of stops costs one fetch.
 */
gl::Texture makeLutTexture(int size, const std::uint8_t* rgba);

/**
 * @brief Scalar raster (data units, NaN = nodata) as RG16F: R = value x validity, G = validity,
 * so linear filtering followed by R/G averages valid neighbours only (nodata never bleeds into
 * values) and G fades smoothly at data edges. RG16F is filterable in core ES 3.0. When
 * `nodataAs` is set, nodata samples become that value with validity 1 (e.g. depth 0 on dry
 * land, so wet/dry fronts interpolate instead of popping).
 */
gl::Texture makeScalarTexture(int width, int height, const float* values,
                              std::optional<float> nodataAs);

/**
 * @brief An encoded normal map (RGBA8 as stored: rgb = normal * 0.5 + 0.5, a = validity, nodata
 * all zero) as a mipmapped RGBA16F texture. Converted once when the tile becomes resident so the
 * hardware filter interpolates in float: one filtered fetch per pixel gives what four 8-bit
 * texel fetches blended in the shader gave (8-bit filtering rounds the filtered normal to 8 bits,
 * up to 1.5 DN of Lambert), which on llvmpipe was the largest share of the demo's shading.
 */
gl::Texture makeNormalMapTexture(int width, int height, const std::uint8_t* rgba);
/** @brief Single-channel 8-bit texture (hillshade, luminance, visibility masks). */
gl::Texture makeR8Texture(int width, int height, const std::uint8_t* values);

}  // namespace kiosk::render
