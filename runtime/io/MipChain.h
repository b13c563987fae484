#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace kiosk::io {

/**
 * @brief A texture's mipmap levels built on the CPU (the loader thread), so the render thread
 * uploads them as they are instead of running glGenerateMipmap (on llvmpipe a blit per level,
 * each a flush of the rasterizer: ~10 ms per 256x256 tile; docs/performance.md §5.2).
 *
 * Levels 1.. down to 1x1 follow level 0 in one buffer; each texel is made from the 2x2 texels
 * below it as llvmpipe's glGenerateMipmap (a linear blit at their midpoint, 8-bit lerps) makes
 * it: the two pairs across averaged and rounded, then those two. MipChainGLTest checks the
 * levels are identical to glGenerateMipmap's. Sizes other than powers of two are left to GL.
 */
struct MipChain {
    /** @brief Whether a width x height RGBA8 image gets its levels here (powers of two). */
    static bool applies(int width, int height);
    /** @brief Bytes of level `level` (RGBA8). */
    static std::size_t levelBytes(int width, int height, int level);
    /** @brief Bytes of levels 0..fullMipLevels()-1 together (TextureBlocks.h counts them). */
    static std::size_t chainBytes(int width, int height);
    /**
     * @brief Append levels 1..fullMipLevels()-1 to `rgba`, which holds level 0 (width x height
     * RGBA8). Returns the level count, or 1 (nothing appended) when !applies() or `rgba` is not
     * exactly one level.
     */
    static int append(std::vector<std::uint8_t>& rgba, int width, int height);
};

}  // namespace kiosk::io
