#pragma once

#include <cstdint>
#include <vector>
#include <vector>

#include "runtime/core/Result.h"
#include "runtime/gl/GlObject.h"

namespace kiosk::gl {

/** @brief Tightly packed RGBA8 pixels, top row first (image order, not GL order). */
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;

    std::uint8_t* pixel(int x, int y) { return &rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4]; }
    const std::uint8_t* pixel(int x, int y) const {
        return &rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4];
    }
};

/**
 * @brief Offscreen framebuffer: RGBA8 colour + 24-bit depth renderbuffers. Used by headless
 * rendering and tests. Render thread only.
 */
class RenderTarget {
public:
    static Result<RenderTarget> create(int width, int height);
    /** @brief RGBA32F colour (needs EXT_color_buffer_float; GL_FRAMEBUFFER_INCOMPLETE without). */
    static Result<RenderTarget> createFloat(int width, int height);

    void bind() const;
    int width() const noexcept { return mWidth; }
    int height() const noexcept { return mHeight; }
    GLuint framebuffer() const noexcept { return mFbo.id(); }

    /** @brief Read the colour buffer into an image, flipped to top-row-first. */
    Image readColor() const;
    /** @brief Read the colour buffer as GL stores it (RGBA8, bottom row first, tightly packed)
     * into `dst` (width*height*4 bytes): no allocation, no flip (the video export's readback). */
    void readInto(std::uint8_t* dst) const;
    /** @brief Float target only: RGBA floats, top row first. */
    std::vector<float> readFloat() const;

private:
    static Result<RenderTarget> create(int width, int height, GLenum colorFormat);
    Framebuffer mFbo;
    Renderbuffer mColor;
    Renderbuffer mDepth;
    int mWidth = 0;
    int mHeight = 0;
};

/** @brief Read the currently bound read framebuffer (window or FBO), top row first. */
Image readPixels(int width, int height);

}  // namespace kiosk::gl
