#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "runtime/core/Result.h"
#include "runtime/gl/GlObject.h"
#include "runtime/math/Glm.h"
#include "runtime/render/FontAtlas.h"

namespace kiosk::render {

/**
 * @brief Screen-space 2D overlay: solid rectangles, text and image strips (legend colour bars),
 * batched into one vertex buffer and drawn with alpha blending after the 3D pass.
 * Coordinates in pixels, origin top-left. Render thread only. Vertex storage is reused across
 * frames (no allocation once warm).
 */
class OverlayRenderer {
public:
    static Result<OverlayRenderer> create(const std::string& fontPath, int pixelSize);

    void begin(int viewportWidth, int viewportHeight);
    void rect(float x, float y, float w, float h, glm::vec4 color);
    /** @brief Draw UTF-8 text with its baseline at y; returns the advance width in pixels. */
    float text(float x, float y, std::string_view utf8, glm::vec4 color);
    float measure(std::string_view utf8) const;
    /** @brief A strip textured left-to-right with `texture` (e.g. a LUT); flushes on change. */
    void image(float x, float y, float w, float h, GLuint texture);
    /** @brief Draw everything queued since begin(). */
    void end();

    const FontAtlas& font() const noexcept { return mFont; }

private:
    void quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1,
              glm::vec4 c, float mode);
    void flush();

    FontAtlas mFont;
    gl::Program mProgram;
    gl::Texture mAtlas;
    gl::Buffer mVbo;
    gl::VertexArray mVao;
    GLint mLocViewport = -1, mLocAtlas = -1, mLocImage = -1;
    GLuint mImage = 0;
    std::vector<float> mVertices;
    std::size_t mVboCapacity = 0;
    int mWidth = 0, mHeight = 0;
};

}  // namespace kiosk::render
