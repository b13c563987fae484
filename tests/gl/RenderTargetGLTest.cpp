// gl::RenderTarget and gl::readPixels: images come back top row first, whatever GL's origin.
#include "runtime/gl/RenderTarget.h"
#include "tests/support/EglTestContext.h"

#include <array>

namespace kiosk::gl {
namespace {

using Rgba = std::array<std::uint8_t, 4>;

Rgba at(const Image& img, int x, int y) {
    const auto* p = img.pixel(x, y);
    return {p[0], p[1], p[2], p[3]};
}

class RenderTargetGLTest : public test::EglTest {
protected:
    /** @brief Clear green, the top half (GL's upper y range) red, the top-left quadrant blue. */
    void paintQuadrants(int w, int h) {
        glDisable(GL_SCISSOR_TEST);
        glClearColor(0, 1, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, h - h / 2, w, h / 2);  // GL y grows upwards: the top rows
        glClearColor(1, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        glScissor(0, h - h / 2, w / 2, h / 2);
        glClearColor(0, 0, 1, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_SCISSOR_TEST);
    }
};

const Rgba kRed{255, 0, 0, 255}, kGreen{0, 255, 0, 255}, kBlue{0, 0, 255, 255};

TEST_F(RenderTargetGLTest, ReadColorIsTopRowFirst) {
    for (const auto& [w, h] : {std::pair{8, 6}, std::pair{5, 7}}) {  // even and odd heights
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        auto rt = makeTarget(w, h);
        paintQuadrants(w, h);
        const Image img = rt.readColor();
        EXPECT_GL_OK();
        ASSERT_EQ(img.width, w);
        ASSERT_EQ(img.height, h);
        ASSERT_EQ(img.rgba.size(), std::size_t(w * h * 4));
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const bool top = y < h / 2, left = x < w / 2;
                const Rgba want = top ? (left ? kBlue : kRed) : kGreen;
                ASSERT_EQ(at(img, x, y), want) << "pixel " << x << "," << y;
            }
        }
    }
}

TEST_F(RenderTargetGLTest, ReadPixelsOfBoundFramebufferIsTopRowFirst) {
    auto rt = makeTarget(4, 4);
    paintQuadrants(4, 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, rt.framebuffer());
    const Image img = readPixels(4, 4);
    EXPECT_EQ(at(img, 0, 0), kBlue);
    EXPECT_EQ(at(img, 3, 0), kRed);
    EXPECT_EQ(at(img, 0, 3), kGreen);
}

TEST_F(RenderTargetGLTest, BindSetsFramebufferAndViewport) {
    auto a = makeTarget(16, 8);
    auto b = makeTarget(3, 5);  // makeTarget binds b
    GLint viewport[4] = {};
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(viewport[2], 3);
    EXPECT_EQ(viewport[3], 5);
    a.bind();
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(viewport[0], 0);
    EXPECT_EQ(viewport[1], 0);
    EXPECT_EQ(viewport[2], 16);
    EXPECT_EQ(viewport[3], 8);
    GLint bound = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &bound);
    EXPECT_EQ(GLuint(bound), a.framebuffer());
    EXPECT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    EXPECT_NE(a.framebuffer(), b.framebuffer());
}

TEST_F(RenderTargetGLTest, HasDepthBuffer) {
    auto rt = makeTarget(2, 2);
    GLint depthBits = 0;
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                                          GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &depthBits);
    EXPECT_GE(depthBits, 24);
    EXPECT_GL_OK();
}

TEST_F(RenderTargetGLTest, EmptySizeIsAnIncompleteFramebuffer) {
    auto rt = RenderTarget::create(0, 0);
    ASSERT_FALSE(rt.ok());
    EXPECT_TRUE(rt.diagnostics.has("GL_FRAMEBUFFER_INCOMPLETE")) << rt.diagnostics.format();
    EXPECT_NE(rt.diagnostics.format().find("0x0"), std::string::npos) << rt.diagnostics.format();
    while (glGetError() != GL_NO_ERROR) {
    }
}

}  // namespace
}  // namespace kiosk::gl
