#pragma once

#include <cstdint>

#include "runtime/gl/GlObject.h"

namespace kiosk::render {

/** @brief RGBA8 2D texture from tightly packed pixels (top row first), linear, clamped. */
gl::Texture makeRgbaTexture(int width, int height, const std::uint8_t* rgba, bool mipmaps);

/**
 * @brief A transfer-function LUT as a `size x 1` RGBA8 texture sampled with LINEAR filtering
 * so that any number of stops costs one fetch.
 */
gl::Texture makeLutTexture(int size, const std::uint8_t* rgba);

}  // namespace kiosk::render
