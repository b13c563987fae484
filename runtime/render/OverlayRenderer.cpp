#include "runtime/render/OverlayRenderer.h"

#include <cmath>

#include "runtime/gl/ProgramBuilder.h"

namespace kiosk::render {
namespace {
constexpr int kFloatsPerVertex = 9;  // pos2 uv2 color4 mode1
}

Result<OverlayRenderer> OverlayRenderer::create(const std::string& fontPath, int pixelSize) {
    auto font = FontAtlas::build(fontPath, pixelSize);
    if (!font) return font.diagnostics;
    auto program = gl::buildProgram("overlay.vert", "overlay.frag");
    if (!program) return program.diagnostics;
    OverlayRenderer r;
    r.mFont = std::move(*font.value);
    r.mProgram = std::move(*program.value);
    r.mLocViewport = glGetUniformLocation(r.mProgram.id(), "uViewport");
    r.mLocAtlas = glGetUniformLocation(r.mProgram.id(), "uAtlas");
    r.mLocImage = glGetUniformLocation(r.mProgram.id(), "uImage");
    r.mAtlas = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, r.mAtlas.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, r.mFont.width(), r.mFont.height(), 0, GL_RED,
                 GL_UNSIGNED_BYTE, r.mFont.pixels().data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    r.mVbo = gl::Buffer::create();
    r.mVao = gl::VertexArray::create();
    glBindVertexArray(r.mVao.id());
    glBindBuffer(GL_ARRAY_BUFFER, r.mVbo.id());
    constexpr GLsizei stride = kFloatsPerVertex * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(2 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(4 * sizeof(float)));
    glEnableVertexAttribArray(3);
    glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(8 * sizeof(float)));
    glBindVertexArray(0);
    r.mVertices.reserve(6 * kFloatsPerVertex * 512);
    return r;
}

void OverlayRenderer::begin(int viewportWidth, int viewportHeight) {
    mWidth = viewportWidth;
    mHeight = viewportHeight;
    mVertices.clear();
    mImage = 0;
}

void OverlayRenderer::quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1,
                           float v1, glm::vec4 c, float mode) {
    const float v[6][4] = {{x0, y0, u0, v0}, {x1, y0, u1, v0}, {x1, y1, u1, v1},
                           {x0, y0, u0, v0}, {x1, y1, u1, v1}, {x0, y1, u0, v1}};
    for (const auto& p : v) {
        mVertices.insert(mVertices.end(), {p[0], p[1], p[2], p[3], c.r, c.g, c.b, c.a, mode});
    }
}

void OverlayRenderer::rect(float x, float y, float w, float h, glm::vec4 color) {
    quad(x, y, x + w, y + h, 0, 0, 0, 0, color, 0.0f);
}

float OverlayRenderer::measure(std::string_view utf8) const {
    float w = 0;
    forEachLatin1(utf8, [&](unsigned char c) { w += mFont.glyph(c)->advance; });
    return w;
}

float OverlayRenderer::text(float x, float y, std::string_view utf8, glm::vec4 color) {
    const float iw = 1.0f / float(mFont.width()), ih = 1.0f / float(mFont.height());
    float pen = x;
    forEachLatin1(utf8, [&](unsigned char ch) {
        const Glyph* g = mFont.glyph(ch);
        if (g->width > 0 && g->height > 0) {
            // Snap to whole pixels: nearest-filtered glyphs stay crisp.
            const float gx = std::floor(pen + 0.5f) + float(g->bearingX);
            const float gy = std::floor(y + 0.5f) - float(g->bearingY);
            quad(gx, gy, gx + float(g->width), gy + float(g->height), float(g->x) * iw,
                 float(g->y) * ih, float(g->x + g->width) * iw, float(g->y + g->height) * ih,
                 color, 1.0f);
        }
        pen += g->advance;
    });
    return pen - x;
}

void OverlayRenderer::image(float x, float y, float w, float h, GLuint texture) {
    if (mImage != 0 && mImage != texture) flush();
    mImage = texture;
    quad(x, y, x + w, y + h, 0.0f, 0.5f, 1.0f, 0.5f, glm::vec4(1.0f), 2.0f);
}

void OverlayRenderer::flush() {
    if (mVertices.empty()) return;
    glUseProgram(mProgram.id());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUniform2f(mLocViewport, float(mWidth), float(mHeight));
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, mAtlas.id());
    glUniform1i(mLocAtlas, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, mImage != 0 ? mImage : mAtlas.id());
    glUniform1i(mLocImage, 1);
    glBindVertexArray(mVao.id());
    glBindBuffer(GL_ARRAY_BUFFER, mVbo.id());
    const std::size_t bytes = mVertices.size() * sizeof(float);
    if (bytes > mVboCapacity) {
        mVboCapacity = bytes * 2;
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mVboCapacity), nullptr, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(bytes), mVertices.data());
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(mVertices.size() / kFloatsPerVertex));
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    mVertices.clear();
}

void OverlayRenderer::end() {
    flush();
    mImage = 0;
}

}  // namespace kiosk::render
