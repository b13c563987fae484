#include "runtime/gl/RenderTarget.h"

#include <cstdio>
#include <algorithm>
#include <cstring>
#include <string>

namespace kiosk::gl {

namespace {
std::string hex(GLenum value) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04X", value);
    return buf;
}
}  // namespace

Result<RenderTarget> RenderTarget::create(int width, int height) {
    return create(width, height, GL_RGBA8);
}

Result<RenderTarget> RenderTarget::createFloat(int width, int height) {
    return create(width, height, GL_RGBA32F);
}

Result<RenderTarget> RenderTarget::create(int width, int height, GLenum colorFormat) {
    RenderTarget rt;
    rt.mWidth = width;
    rt.mHeight = height;
    rt.mFbo = Framebuffer::create();
    rt.mColor = Renderbuffer::create();
    rt.mDepth = Renderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, rt.mColor.id());
    glRenderbufferStorage(GL_RENDERBUFFER, colorFormat, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, rt.mDepth.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, rt.mFbo.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rt.mColor.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rt.mDepth.id());
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        Diagnostics d;
        d.error("GL_FRAMEBUFFER_INCOMPLETE", "", "",
                "offscreen framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                    " is incomplete (status " + hex(status) + ")");
        return d;
    }
    return rt;
}

void RenderTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, mFbo.id());
    glViewport(0, 0, mWidth, mHeight);
}

Image RenderTarget::readColor() const {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mFbo.id());
    return readPixels(mWidth, mHeight);
}

void RenderTarget::readInto(std::uint8_t* dst) const {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mFbo.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, mWidth, mHeight, GL_RGBA, GL_UNSIGNED_BYTE, dst);
}

std::vector<float> RenderTarget::readFloat() const {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mFbo.id());
    std::vector<float> px(std::size_t(mWidth) * std::size_t(mHeight) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, mWidth, mHeight, GL_RGBA, GL_FLOAT, px.data());
    const std::size_t stride = std::size_t(mWidth) * 4;
    for (int y = 0; y < mHeight / 2; ++y)
        std::swap_ranges(px.begin() + std::ptrdiff_t(std::size_t(y) * stride),
                         px.begin() + std::ptrdiff_t(std::size_t(y + 1) * stride),
                         px.begin() + std::ptrdiff_t(std::size_t(mHeight - 1 - y) * stride));
    return px;
}

Image readPixels(int width, int height) {
    Image img;
    img.width = width;
    img.height = height;
    img.rgba.resize(std::size_t(width) * std::size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
    // GL's origin is bottom-left; images are stored top row first.
    const std::size_t stride = std::size_t(width) * 4;
    std::vector<std::uint8_t> tmp(stride);
    for (int y = 0; y < height / 2; ++y) {
        auto* a = img.rgba.data() + std::size_t(y) * stride;
        auto* b = img.rgba.data() + std::size_t(height - 1 - y) * stride;
        std::memcpy(tmp.data(), a, stride);
        std::memcpy(a, b, stride);
        std::memcpy(b, tmp.data(), stride);
    }
    return img;
}

}  // namespace kiosk::gl
