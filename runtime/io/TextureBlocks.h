#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/core/TileId.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

// GPU block-compressed textures kept beside an imagery layer's PNG tiles (table
// kiosk_tile_textures, docs/store-format.md; Wahl et al. 2004 §4 keep their textures
// S3TC-compressed). Encoded at import (runtime/import/TextureCompression.h); the loader reads the
// blocks as stored and the render thread hands them to glCompressedTexImage2D: nothing is
// decoded on the CPU at run time. Values through a LUT (sequences, elevation) are never stored
// this way: only imagery (RGBA) layers are.
namespace kiosk::io {

/** @brief Block formats a store can hold (kiosk_tile_textures.format). */
enum class TextureFormat { None, Astc4x4 };

/** @brief The stored name ("astc_4x4"), "none" for None. */
const char* textureFormatName(TextureFormat f) noexcept;
std::optional<TextureFormat> parseTextureFormat(const std::string& name) noexcept;

/** @brief Bytes of one image of width x height in `f` (partial blocks at the edges count whole). */
std::size_t textureImageBytes(TextureFormat f, int width, int height) noexcept;
/** @brief Levels of a full mip chain down to 1 x 1: floor(log2(max(w, h))) + 1. */
int fullMipLevels(int width, int height) noexcept;

/** @brief Largest tile side a stored texture may have (the decoder's bound before allocating). */
inline constexpr int kMaxTextureSide = 8192;

/**
 * @brief One imagery tile as GPU blocks: `levels` mip levels, level 0 first, each level's blocks
 * row-major from the tile's top-left (the PNG's first row), level k of size max(1, w >> k).
 */
struct CompressedImage {
    TileId id;
    TextureFormat format = TextureFormat::None;
    int width = 0;
    int height = 0;
    int levels = 0;
    std::vector<std::uint8_t> blocks;

    /** @brief Byte offset of level `level` in `blocks`. */
    std::size_t levelOffset(int level) const noexcept;
    /** @brief Bytes of all `levels` levels (what `blocks` must hold). */
    std::size_t expectedBytes() const noexcept;
    int levelWidth(int level) const noexcept { return std::max(1, width >> level); }
    int levelHeight(int level) const noexcept { return std::max(1, height >> level); }
};

/**
 * @brief A row as read from the store is usable: known format, sides in 1..kMaxTextureSide,
 * 1..fullMipLevels levels, a blob of `blobBytes` exactly as long as those levels (`image.blocks`
 * is not looked at: checked before the blob is copied). STORE_TEXTURE_CORRUPT naming `where`
 * (table/level/column/row) otherwise.
 */
Diagnostics checkCompressedImage(const CompressedImage& image, std::size_t blobBytes,
                                 const std::string& file, const std::string& where);

}  // namespace kiosk::io
