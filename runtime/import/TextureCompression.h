#pragma once

#include "runtime/core/Result.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

// `geokiosk import textures` (docs/cli.md, docs/terrain.md §11): the imagery layers of an
// existing store encoded as ASTC 4x4 GPU blocks with Debian's astcenc, every mip level, kept in
// kiosk_tile_textures beside the PNG tiles (io/TextureBlocks.h). Data layers (elevation,
// sequences: values through a LUT) are never lossy-compressed and are refused by name.
namespace kiosk::import {

/** @brief astcenc's quality presets (the `--quality` words). */
enum class AstcQuality { Fast, Medium, Thorough };

struct TextureImportOptions {
    std::filesystem::path store;
    std::vector<std::string> layers;  ///< imagery layers; empty: every imagery layer
    AstcQuality quality = AstcQuality::Medium;
    int threads = 2;
    bool quiet = false;
};

/** @brief What one layer got (the command's report, the benchmark's figures). */
struct TextureLayerReport {
    std::string layer;
    std::size_t tiles = 0;
    double psnrMinDb = 0;  ///< level 0 against the PNG, RGB
    double psnrMedianDb = 0;
    std::size_t rgbaBytes = 0;   ///< RGBA8 with the full mip chain (what the PNGs expand to)
    std::size_t blockBytes = 0;  ///< stored blocks, every level
    double encodeCpuMs = 0;      ///< astcenc, summed over threads
};

/**
 * @brief Encode and store (replacing a layer's earlier blocks). Atomic like every import (a
 * temporary copy renamed into place). Errors: IMPORT_USAGE (no store, unknown layer, a data
 * layer), IMPORT_TEXTURE (the encoder failed), store errors naming file and tile.
 */
Result<std::vector<TextureLayerReport>> importTextureBlocks(const TextureImportOptions& options);

}  // namespace kiosk::import
