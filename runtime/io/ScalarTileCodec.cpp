#include "runtime/io/ScalarTileCodec.h"

#include "runtime/io/ImageCodec.h"
#include "runtime/io/ImageHeader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace kiosk::io {

bool quantizePosts(std::vector<float>& posts, double scale) {
    bool any = false;
    for (float& v : posts) {
        if (std::isnan(v)) continue;
        v = float(std::nearbyint(double(v) / scale) * scale);
        any = true;
    }
    return any;
}

Result<EncodedScalarTile> encodeScalarTile(const std::vector<float>& posts, int tileWidth,
                                           int tileHeight, double scale, int pngLevel) {
    EncodedScalarTile t;
    const int pw = tileWidth + 1;
    float mn = std::numeric_limits<float>::infinity(), mx = -mn;
    for (float v : posts) {
        if (std::isnan(v)) continue;
        mn = std::min(mn, v);
        mx = std::max(mx, v);
    }
    if (!(mn <= mx)) mn = mx = 0;
    t.stats.minValue = mn;
    t.stats.maxValue = mx;
    t.scale = scale;
    // Offset is a multiple of the scale, so raw values are exact integers of the quantised posts.
    t.offset = std::floor(double(mn) / scale) * scale;
    std::vector<std::uint16_t> raw(std::size_t(tileWidth) * std::size_t(tileHeight));
    for (int y = 0; y < tileHeight; ++y) {
        for (int x = 0; x < tileWidth; ++x) {
            const float v = posts[std::size_t(y) * std::size_t(pw) + std::size_t(x)];
            std::uint16_t r = kNodataRaw;
            if (!std::isnan(v)) {
                double q = std::nearbyint((double(v) - t.offset) / scale);
                if (q > kMaxRaw) {
                    q = kMaxRaw;
                    t.clamped = true;
                }
                r = std::uint16_t(std::max(0.0, q));
            }
            raw[std::size_t(y) * std::size_t(tileWidth) + std::size_t(x)] = r;
        }
    }
    t.border.reserve(std::size_t(tileHeight + 1 + tileWidth));
    for (int y = 0; y <= tileHeight; ++y)
        t.border.push_back(posts[std::size_t(y) * std::size_t(pw) + std::size_t(tileWidth)]);
    for (int x = 0; x < tileWidth; ++x)
        t.border.push_back(posts[std::size_t(tileHeight) * std::size_t(pw) + std::size_t(x)]);
    auto png = encodePng16(raw.data(), tileWidth, tileHeight, pngLevel);
    if (!png) return png.diagnostics;
    t.png = std::move(*png);
    return t;
}

Result<RasterTile> decodeScalarTile(const std::uint8_t* png, std::size_t pngSize,
                                    const std::uint8_t* border, std::size_t borderSize,
                                    double scale, double offset, double dataNull, int tileWidth,
                                    int tileHeight, const std::string& where) {
    // Format, depth, channels and size from the header, before any decoding (issue 13: an RGB8
    // PNG decoded as grey garbles the terrain; a bomb's size was only checked after decoding).
    Diagnostics d = checkTileHeader(png, pngSize, {tileWidth, tileHeight, true}, where);
    if (d.hasErrors()) return d;
    auto img = decodeGray16(png, pngSize, where);
    if (!img) return img.diagnostics;
    if (img->width != tileWidth || img->height != tileHeight) {
        d.error("STORE_TILE_CORRUPT", "", where,
                "tile is " + std::to_string(img->width) + "x" + std::to_string(img->height) +
                    ", expected " + std::to_string(tileWidth) + "x" + std::to_string(tileHeight));
        return d;
    }
    const std::size_t borderCount = std::size_t(tileHeight + 1 + tileWidth);
    if (border && borderSize != 0 && borderSize != borderCount * sizeof(float)) {
        d.error("STORE_TILE_CORRUPT", "", where,
                "border posts blob has " + std::to_string(borderSize) + " bytes, expected " +
                    std::to_string(borderCount * sizeof(float)));
        return d;
    }
    RasterTile t;
    t.postsX = tileWidth + 1;
    t.postsY = tileHeight + 1;
    t.values.assign(std::size_t(t.postsX) * std::size_t(t.postsY),
                    std::numeric_limits<float>::quiet_NaN());
    const auto nullRaw = dataNull;
    for (int y = 0; y < tileHeight; ++y) {
        for (int x = 0; x < tileWidth; ++x) {
            const std::uint16_t r =
                img->samples16[std::size_t(y) * std::size_t(tileWidth) + std::size_t(x)];
            if (double(r) == nullRaw) continue;
            t.values[std::size_t(y) * std::size_t(t.postsX) + std::size_t(x)] =
                float(double(r) * scale + offset);
        }
    }
    if (border && borderSize != 0) {
        std::vector<float> b(borderCount);
        std::memcpy(b.data(), border, borderSize);
        for (int y = 0; y <= tileHeight; ++y)
            t.values[std::size_t(y) * std::size_t(t.postsX) + std::size_t(tileWidth)] =
                b[std::size_t(y)];
        for (int x = 0; x < tileWidth; ++x)
            t.values[std::size_t(tileHeight) * std::size_t(t.postsX) + std::size_t(x)] =
                b[std::size_t(tileHeight + 1 + x)];
    } else {
        for (int y = 0; y < tileHeight; ++y)
            t.values[std::size_t(y) * std::size_t(t.postsX) + std::size_t(tileWidth)] =
                t.values[std::size_t(y) * std::size_t(t.postsX) + std::size_t(tileWidth - 1)];
        for (int x = 0; x <= tileWidth; ++x)
            t.values[std::size_t(tileHeight) * std::size_t(t.postsX) + std::size_t(x)] =
                t.values[std::size_t(tileHeight - 1) * std::size_t(t.postsX) + std::size_t(x)];
    }
    return t;
}

}  // namespace kiosk::io
