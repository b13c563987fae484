#pragma once

#include <cstdint>
#include <optional>

#include "runtime/gl/GlObject.h"
#include "runtime/io/TextureBlocks.h"

namespace kiosk::render {

/** @brief RGBA8 2D texture from tightly packed pixels (top row first), linear, clamped. */
gl::Texture makeRgbaTexture(int width, int height, const std::uint8_t* rgba, bool mipmaps);

/**
 * @brief GPU blocks stored at import (io::CompressedImage, checked when read) as a compressed
 * texture, its levels as stored (glCompressedTexImage2D each; GL_TEXTURE_MAX_LEVEL = levels - 1
 * keeps a partial chain complete), linear filtering between levels as makeRgbaTexture's mipmaps,
 * clamped. The caller checked the context has the format (scene/TextureChoice.h).
 */
gl::Texture makeCompressedTexture(const io::CompressedImage& image);

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
 * @brief A derived product's tile (layers/products/): width x height texels of 4 floats, stored
 * RGBA16F as given (the product's state and the frame pair, one texture read per fragment),
 * linear filtering, clamped.
 */
gl::Texture makeProductTexture(int width, int height, const float* rgba);

/** @brief Single-channel 8-bit texture (hillshade, luminance, visibility masks). */
gl::Texture makeR8Texture(int width, int height, const std::uint8_t* values);

}  // namespace kiosk::render
