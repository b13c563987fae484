#include "runtime/io/TextureBlocks.h"

#include <algorithm>

namespace kiosk::io {

const char* textureFormatName(TextureFormat f) noexcept {
    switch (f) {
        case TextureFormat::Astc4x4:
            return "astc_4x4";
        case TextureFormat::None:
            break;
    }
    return "none";
}

std::optional<TextureFormat> parseTextureFormat(const std::string& name) noexcept {
    if (name == "astc_4x4") return TextureFormat::Astc4x4;
    return std::nullopt;
}

std::size_t textureImageBytes(TextureFormat f, int width, int height) noexcept {
    if (f != TextureFormat::Astc4x4 || width <= 0 || height <= 0) return 0;
    return std::size_t((width + 3) / 4) * std::size_t((height + 3) / 4) * 16;  // 128-bit blocks
}

int fullMipLevels(int width, int height) noexcept {
    int levels = 1;
    for (int side = std::max(width, height); side > 1; side >>= 1) ++levels;
    return levels;
}

std::size_t CompressedImage::levelOffset(int level) const noexcept {
    std::size_t offset = 0;
    for (int k = 0; k < level; ++k)
        offset += textureImageBytes(format, levelWidth(k), levelHeight(k));
    return offset;
}

std::size_t CompressedImage::expectedBytes() const noexcept {
    return levelOffset(levels);
}

Diagnostics checkCompressedImage(const CompressedImage& image, std::size_t blobBytes,
                                 const std::string& file, const std::string& where) {
    Diagnostics d;
    std::string problem;
    if (image.format == TextureFormat::None)
        problem = "unknown block format";
    else if (image.width < 1 || image.height < 1 || image.width > kMaxTextureSide ||
             image.height > kMaxTextureSide)
        problem = "size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                  " out of range";
    else if (image.levels < 1 || image.levels > fullMipLevels(image.width, image.height))
        problem = std::to_string(image.levels) + " mip levels for a " +
                  std::to_string(image.width) + "x" + std::to_string(image.height) + " tile";
    else if (blobBytes != image.expectedBytes())
        problem = std::to_string(blobBytes) + " bytes of blocks, " +
                  std::to_string(image.expectedBytes()) + " expected";
    if (!problem.empty())
        d.error("STORE_TEXTURE_CORRUPT", file, where,
                std::string("stored ") + textureFormatName(image.format) + " texture: " + problem);
    return d;
}

}  // namespace kiosk::io
