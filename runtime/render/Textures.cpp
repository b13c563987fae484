#include "runtime/render/Textures.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/packing.hpp>
#include <vector>

namespace kiosk::render {

gl::Texture makeRgbaTexture(int width, int height, const std::uint8_t* rgba, bool mipmaps) {
    auto tex = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, tex.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    if (mipmaps) {
        glGenerateMipmap(GL_TEXTURE_2D);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    } else {
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    }
    return tex;
}

gl::Texture makeLutTexture(int size, const std::uint8_t* rgba) {
    return makeRgbaTexture(size, 1, rgba, false);
}

namespace {
void setLinearClamp() {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
}
}  // namespace

gl::Texture makeScalarTexture(int width, int height, const float* values,
                              std::optional<float> nodataAs) {
    std::vector<float> rg(std::size_t(width) * std::size_t(height) * 2);
    for (std::size_t i = 0, n = rg.size() / 2; i < n; ++i) {
        const float v = values[i];
        if (std::isnan(v)) {
            rg[i * 2] = nodataAs.value_or(0.0f);
            rg[i * 2 + 1] = nodataAs ? 1.0f : 0.0f;
        } else {
            rg[i * 2] = v;
            rg[i * 2 + 1] = 1.0f;
        }
    }
    auto tex = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, tex.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG16F, width, height, 0, GL_RG, GL_FLOAT, rg.data());
    setLinearClamp();
    return tex;
}

gl::Texture makeNormalMapTexture(int width, int height, const std::uint8_t* rgba) {
    // Level 0 and the mip chain (2x2 box, as glGenerateMipmap, which core ES 3.0 cannot do for
    // RGBA16F: filterable but not colour-renderable) are built in float and uploaded as half
    // floats, which hold every k/255 to 2^-11 relative, well inside the 8-bit step. The scratch
    // buffers are reused (render thread only): a tile upload then allocates nothing on the heap.
    thread_local std::vector<float> level, next;
    thread_local std::vector<std::uint16_t> half;
    level.resize(std::size_t(width) * std::size_t(height) * 4);
    for (std::size_t i = 0; i < level.size(); ++i) level[i] = float(rgba[i]) * (1.0f / 255.0f);
    int levels = 1;
    for (int m = std::max(width, height); m > 1; m /= 2) ++levels;
    auto tex = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, tex.id());
    // Immutable storage: the whole chain allocated once (per-level glTexImage2D made Mesa build
    // each level apart and copy them together on first use).
    glTexStorage2D(GL_TEXTURE_2D, levels, GL_RGBA16F, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    for (int l = 0, w = width, h = height; l < levels; ++l) {
        half.resize(std::size_t(w) * std::size_t(h) * 4);
        for (std::size_t i = 0; i < half.size(); ++i) half[i] = glm::packHalf1x16(level[i]);
        glTexSubImage2D(GL_TEXTURE_2D, l, 0, 0, w, h, GL_RGBA, GL_HALF_FLOAT, half.data());
        if (l + 1 == levels) break;
        const int nw = std::max(1, w / 2), nh = std::max(1, h / 2);
        next.assign(std::size_t(nw) * std::size_t(nh) * 4, 0.0f);
        for (int y = 0; y < nh; ++y)
            for (int x = 0; x < nw; ++x)
                for (int k = 0; k < 4; ++k) {
                    const std::size_t sx = std::size_t(std::min(w - 1, 2 * x + (k & 1)));
                    const std::size_t sy = std::size_t(std::min(h - 1, 2 * y + (k >> 1)));
                    const float* src = &level[(sy * std::size_t(w) + sx) * 4];
                    float* dst = &next[(std::size_t(y) * std::size_t(nw) + std::size_t(x)) * 4];
                    for (int c = 0; c < 4; ++c) dst[c] += 0.25f * src[c];
                }
        level.swap(next);
        w = nw, h = nh;
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    return tex;
}

gl::Texture makeR8Texture(int width, int height, const std::uint8_t* values) {
    auto tex = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, tex.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, width, height, 0, GL_RED, GL_UNSIGNED_BYTE, values);
    setLinearClamp();
    return tex;
}

}  // namespace kiosk::render
