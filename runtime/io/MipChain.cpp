#include "runtime/io/MipChain.h"

#include "runtime/io/TextureBlocks.h"

#include <algorithm>

namespace kiosk::io {

namespace {
bool powerOfTwo(int v) {
    return v > 0 && (v & (v - 1)) == 0;
}
}  // namespace

bool MipChain::applies(int width, int height) {
    return powerOfTwo(width) && powerOfTwo(height);
}

std::size_t MipChain::levelBytes(int width, int height, int level) {
    return std::size_t(std::max(1, width >> level)) * std::size_t(std::max(1, height >> level)) * 4;
}

std::size_t MipChain::chainBytes(int width, int height) {
    std::size_t bytes = 0;
    for (int l = 0, n = fullMipLevels(width, height); l < n; ++l)
        bytes += levelBytes(width, height, l);
    return bytes;
}

int MipChain::append(std::vector<std::uint8_t>& rgba, int width, int height) {
    if (!applies(width, height) || rgba.size() != levelBytes(width, height, 0)) return 1;
    const int levels = fullMipLevels(width, height);
    rgba.resize(chainBytes(width, height));
    std::size_t srcOffset = 0;
    for (int l = 1; l < levels; ++l) {
        const int sw = std::max(1, width >> (l - 1)), sh = std::max(1, height >> (l - 1));
        const int dw = std::max(1, width >> l), dh = std::max(1, height >> l);
        const std::uint8_t* src = rgba.data() + srcOffset;
        std::uint8_t* dst = rgba.data() + srcOffset + levelBytes(width, height, l - 1);
        // A side already at 1 texel averages the two texels of the other side only.
        const int dx = sw > 1 ? 1 : 0, dy = sh > 1 ? 1 : 0;
        for (int y = 0; y < dh; ++y) {
            const std::uint8_t* row0 = src + std::size_t(2 * y) * std::size_t(sw) * 4;
            const std::uint8_t* row1 = row0 + std::size_t(dy) * std::size_t(sw) * 4;
            for (int x = 0; x < dw; ++x) {
                const std::size_t a = std::size_t(2 * x) * 4, b = a + std::size_t(dx) * 4;
                std::uint8_t* out = dst + (std::size_t(y) * std::size_t(dw) + std::size_t(x)) * 4;
                for (std::size_t c = 0; c < 4; ++c) {
                    // llvmpipe's 8-bit bilinear at the midpoint: across, then down, each rounded.
                    const int top = (row0[a + c] + row0[b + c] + 1) >> 1;
                    const int bottom = (row1[a + c] + row1[b + c] + 1) >> 1;
                    out[c] = std::uint8_t((top + bottom + 1) >> 1);
                }
            }
        }
        srcOffset += levelBytes(width, height, l - 1);
    }
    return levels;
}

}  // namespace kiosk::io
