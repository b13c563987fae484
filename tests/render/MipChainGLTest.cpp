// io::MipChain (levels built on the loader thread) against llvmpipe's glGenerateMipmap (the same
// texels, level by level), and render::makeRgbaTextureLevels uploading them as they are
// (docs/performance.md §5.2).
#include "runtime/io/MipChain.h"
#include "runtime/io/TextureBlocks.h"
#include "runtime/render/Textures.h"
#include "tests/support/EglTestContext.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace kiosk::render {
namespace {

class MipChainGLTest : public test::EglTest {};

std::vector<std::uint8_t> noiseImage(int w, int h, unsigned seed) {
    std::vector<std::uint8_t> rgba(std::size_t(w) * std::size_t(h) * 4);
    unsigned x = seed;
    for (auto& v : rgba) {
        x = x * 1664525u + 1013904223u;
        v = std::uint8_t(x >> 24);
    }
    return rgba;
}

std::vector<std::uint8_t> readTextureLevel(GLuint tex, int level, int w, int h) {
    GLuint fbo = 0;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, level);
    std::vector<std::uint8_t> out(std::size_t(w) * std::size_t(h) * 4);
    EXPECT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    return out;
}

TEST(MipChain, SizesAndLevels) {
    EXPECT_TRUE(io::MipChain::applies(256, 256));
    EXPECT_TRUE(io::MipChain::applies(256, 64));
    EXPECT_FALSE(io::MipChain::applies(257, 256));
    EXPECT_FALSE(io::MipChain::applies(0, 256));
    EXPECT_EQ(io::fullMipLevels(256, 256), 9);
    EXPECT_EQ(io::fullMipLevels(256, 64), 9);
    EXPECT_EQ(io::fullMipLevels(1, 1), 1);
    EXPECT_EQ(io::MipChain::chainBytes(4, 2), std::size_t(4 * 2 * 4 + 2 * 1 * 4 + 1 * 1 * 4));
    // A 2x2 image: one more level, each channel the rounded mean.
    // A 2x2 image: one more level; across rounded, then down rounded (llvmpipe's lerps).
    std::vector<std::uint8_t> px = {0, 10, 255, 61,  1, 10, 255, 12,
                                    2, 11, 254, 215, 4, 11, 254, 106};
    EXPECT_EQ(io::MipChain::append(px, 2, 2), 2);
    ASSERT_EQ(px.size(), std::size_t(20));
    EXPECT_EQ(px[16], 2);    // (1 + 3 + 1) / 2
    EXPECT_EQ(px[17], 11);   // (10 + 11 + 1) / 2
    EXPECT_EQ(px[18], 255);  // (255 + 254 + 1) / 2
    EXPECT_EQ(px[19], 99);   // (37 + 161 + 1) / 2: what llvmpipe makes of 61, 12 / 215, 106
    // Not a power of two, or not exactly one level: left alone.
    std::vector<std::uint8_t> odd(3 * 3 * 4, 7);
    EXPECT_EQ(io::MipChain::append(odd, 3, 3), 1);
    EXPECT_EQ(odd.size(), std::size_t(36));
    EXPECT_EQ(io::MipChain::append(px, 2, 2), 1);  // already a chain
}

TEST_F(MipChainGLTest, LevelsMatchGenerateMipmap) {
    for (auto [w, h] : {std::pair{256, 256}, std::pair{64, 16}}) {
        std::vector<std::uint8_t> chain = noiseImage(w, h, unsigned(w * 31 + h));
        const std::vector<std::uint8_t> base = chain;
        const int levels = io::MipChain::append(chain, w, h);
        ASSERT_EQ(levels, io::fullMipLevels(w, h));
        gl::Texture generated = makeRgbaTexture(w, h, base.data(), true);
        gl::Texture uploaded = makeRgbaTextureLevels(w, h, chain.data(), chain.size());
        std::size_t offset = 0;
        for (int l = 0; l < levels; ++l) {
            const int lw = std::max(1, w >> l), lh = std::max(1, h >> l);
            const auto gpu = readTextureLevel(generated.id(), l, lw, lh);
            const auto ours = readTextureLevel(uploaded.id(), l, lw, lh);
            int maxDiff = 0, differing = 0;
            for (std::size_t i = 0; i < gpu.size(); ++i) {
                EXPECT_EQ(ours[i], chain[offset + i]) << "uploaded as built, level " << l;
                const int d = std::abs(int(gpu[i]) - int(chain[offset + i]));
                maxDiff = std::max(maxDiff, d);
                differing += d != 0;
            }
            std::printf("%dx%d level %d: max diff %d, %d of %zu channels differ\n", w, h, l,
                        maxDiff, differing, gpu.size());
            EXPECT_EQ(maxDiff, 0) << w << "x" << h << " level " << l;
            offset += io::MipChain::levelBytes(w, h, l);
        }
    }
}

}  // namespace
}  // namespace kiosk::render
