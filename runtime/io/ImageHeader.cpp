#include "runtime/io/ImageHeader.h"

#include <algorithm>

namespace kiosk::io {

namespace {

std::uint32_t be32(const std::uint8_t* p) {
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 |
           std::uint32_t(p[3]);
}
std::uint32_t be16(const std::uint8_t* p) {
    return std::uint32_t(p[0]) << 8 | std::uint32_t(p[1]);
}

std::optional<ImageHeader> pngHeader(const std::uint8_t* d, std::size_t n) {
    static const std::uint8_t kSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    // Signature, then the IHDR chunk: length 13, type, width, height, depth, colour type, ...
    if (n < 8 + 8 + 13) return std::nullopt;
    for (int i = 0; i < 8; ++i)
        if (d[i] != kSig[i]) return std::nullopt;
    if (be32(d + 8) != 13 || d[12] != 'I' || d[13] != 'H' || d[14] != 'D' || d[15] != 'R')
        return std::nullopt;
    ImageHeader h;
    h.format = ImageFormat::Png;
    h.width = be32(d + 16);
    h.height = be32(d + 20);
    h.bitDepth = d[24];
    switch (d[25]) {
        case 0:
            h.channels = 1;
            break;
        case 2:
            h.channels = 3;
            break;
        case 3:
            h.channels = 1;
            h.palette = true;
            break;
        case 4:
            h.channels = 2;
            break;
        case 6:
            h.channels = 4;
            break;
        default:
            return std::nullopt;
    }
    return h;
}

std::optional<ImageHeader> jpegHeader(const std::uint8_t* d, std::size_t n) {
    if (n < 4 || d[0] != 0xFF || d[1] != 0xD8) return std::nullopt;
    std::size_t p = 2;
    while (p + 4 <= n) {
        if (d[p] != 0xFF) return std::nullopt;
        const std::uint8_t m = d[p + 1];
        if (m == 0xFF) {  // fill byte
            ++p;
            continue;
        }
        if (m == 0x01 || (m >= 0xD0 && m <= 0xD7)) {  // markers without a length
            p += 2;
            continue;
        }
        if (m == 0xD9 || m == 0xDA) return std::nullopt;  // end / scan before any frame header
        const std::size_t len = be16(d + p + 2);
        if (len < 2) return std::nullopt;
        const bool sof = m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC;
        if (sof) {
            if (p + 2 + 8 > n || len < 8) return std::nullopt;
            ImageHeader h;
            h.format = ImageFormat::Jpeg;
            h.bitDepth = d[p + 4];
            h.height = be16(d + p + 5);
            h.width = be16(d + p + 7);
            h.channels = d[p + 9];
            return h;
        }
        p += 2 + len;
    }
    return std::nullopt;
}

}  // namespace

std::string ImageHeader::describe() const {
    const char* kind = palette         ? "palette"
                       : channels == 1 ? "grey"
                       : channels == 2 ? "grey+alpha"
                       : channels == 3 ? "RGB"
                       : channels == 4 ? "RGBA"
                                       : "multi-channel";
    const char* fmt = format == ImageFormat::Png    ? "PNG"
                      : format == ImageFormat::Jpeg ? "JPEG"
                                                    : "image";
    return std::to_string(bitDepth) + "-bit " + kind + " " + fmt;
}

bool declaresNormalMap(const std::string& description) noexcept {
    return description.rfind("normal map of ", 0) == 0;
}

std::optional<ImageHeader> peekImageHeader(const std::uint8_t* data, std::size_t size) noexcept {
    if (!data) return std::nullopt;
    if (auto h = pngHeader(data, size)) return h;
    return jpegHeader(data, size);
}

Diagnostics checkTileHeader(const std::uint8_t* data, std::size_t size,
                            const TileExpectation& expect, const std::string& where) {
    Diagnostics d;
    const auto h = peekImageHeader(data, size);
    if (!h) {
        d.error("STORE_TILE_CORRUPT", "", where,
                size == 0 ? "tile data is empty" : "tile data is not a PNG or JPEG image");
        return d;
    }
    const bool formatOk = expect.scalar ? h->format == ImageFormat::Png && h->bitDepth == 16 &&
                                              h->channels == 1 && !h->palette
                          : expect.rgb ? h->format == ImageFormat::Png && h->bitDepth == 8 &&
                                             h->channels >= 3 && h->channels <= 4
                                       : h->bitDepth == 8 && h->channels >= 1 && h->channels <= 4;
    if (!formatOk) {
        d.error("STORE_TILE_FORMAT", "", where,
                "tile is a " + h->describe() + "; this table holds " +
                    (expect.scalar ? "16-bit grey PNGs"
                     : expect.rgb  ? "8-bit RGB or RGBA PNGs (a normal map)"
                                   : "8-bit PNGs or JPEGs"));
        return d;
    }
    const std::uint64_t bytes = std::uint64_t(h->width) * h->height * std::uint64_t(h->channels) *
                                std::uint64_t(h->bitDepth > 8 ? 2 : 1);
    if (h->width != std::uint32_t(expect.width) || h->height != std::uint32_t(expect.height) ||
        bytes > kMaxTileDecodeBytes) {
        d.error("STORE_TILE_SIZE", "", where,
                "tile claims " + std::to_string(h->width) + "x" + std::to_string(h->height) +
                    " pixels, the table's tiles are " + std::to_string(expect.width) + "x" +
                    std::to_string(expect.height) + " (not decoded)");
        return d;
    }
    return d;
}

Diagnostics checkDecodeBudget(const std::uint8_t* data, std::size_t size,
                              const std::string& where) {
    Diagnostics d;
    const auto h = peekImageHeader(data, size);
    if (!h) {
        d.error("IMAGE_DECODE", "", where, "tile data has no readable PNG or JPEG header");
        return d;
    }
    const std::uint64_t bytes = std::uint64_t(h->width) * h->height *
                                std::uint64_t(std::max(h->channels, 1)) *
                                std::uint64_t(h->bitDepth > 8 ? 2 : 1);
    if (bytes > kMaxTileDecodeBytes || h->width == 0 || h->height == 0)
        d.error("IMAGE_DECODE", "", where,
                "tile claims " + std::to_string(h->width) + "x" + std::to_string(h->height) +
                    " pixels, over the decode budget of " +
                    std::to_string(kMaxTileDecodeBytes >> 20) + " MiB (not decoded)");
    return d;
}

}  // namespace kiosk::io
