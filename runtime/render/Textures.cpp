#include "runtime/render/Textures.h"

#include "runtime/io/MipChain.h"
#include "runtime/io/TextureBlocks.h"

#include <algorithm>
#include <cmath>
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

gl::Texture makeRgbaTextureLevels(int width, int height, const std::uint8_t* rgba,
                                  std::size_t bytes) {
    if (!io::MipChain::applies(width, height) || bytes != io::MipChain::chainBytes(width, height))
        return makeRgbaTexture(width, height, rgba, true);
    const int levels = io::fullMipLevels(width, height);
    auto tex = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, tex.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexStorage2D(GL_TEXTURE_2D, levels, GL_RGBA8, width, height);
    std::size_t offset = 0;
    for (int level = 0; level < levels; ++level) {
        glTexSubImage2D(GL_TEXTURE_2D, level, 0, 0, std::max(1, width >> level),
                        std::max(1, height >> level), GL_RGBA, GL_UNSIGNED_BYTE, rgba + offset);
        offset += io::MipChain::levelBytes(width, height, level);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    return tex;
}

gl::Texture makeCompressedTexture(const io::CompressedImage& image) {
    // GL_COMPRESSED_RGBA_ASTC_4x4_KHR (KHR_texture_compression_astc_ldr)
    constexpr GLenum kAstc4x4 = 0x93B0;
    auto tex = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, tex.id());
    for (int level = 0; level < image.levels; ++level) {
        const int w = image.levelWidth(level), h = image.levelHeight(level);
        glCompressedTexImage2D(GL_TEXTURE_2D, level, kAstc4x4, w, h, 0,
                               GLsizei(io::textureImageBytes(image.format, w, h)),
                               image.blocks.data() + image.levelOffset(level));
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, image.levels - 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                    image.levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    return tex;
}

gl::Texture makeLutTexture(int size, const std::uint8_t* rgba) {
    return makeRgbaTexture(size, 1, rgba, false);
}

gl::Texture makeEdgedLutTexture(int size, const std::uint8_t* rgba, const glm::vec4& below,
                                const glm::vec4& above, const glm::vec4& nodata) {
    const std::size_t n = std::size_t(std::max(size, 1));
    std::vector<std::uint8_t> texels((n + 3) * 4);
    std::copy(rgba, rgba + n * 4, texels.begin() + 4);
    const auto edge = [&](std::size_t texel, const glm::vec4& c, const std::uint8_t* end) {
        for (int k = 0; k < 4; ++k)
            texels[texel * 4 + std::size_t(k)] =
                c.a >= 0.0f || !end
                    ? std::uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f))
                    : end[k];
    };
    edge(0, below, rgba);
    edge(n + 1, above, rgba + (n - 1) * 4);
    edge(n + 2, nodata, nullptr);
    return makeLutTexture(int(n + 3), texels.data());
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

gl::Texture makeProductTexture(int width, int height, const float* rgba) {
    auto tex = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, tex.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, width, height, 0, GL_RGBA, GL_FLOAT, rgba);
    setLinearClamp();
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
