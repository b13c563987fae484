#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/io/ImageCodec.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

// What an encoded tile says it is, read from its first bytes (PNG IHDR, JPEG SOFn) without a
// decoder: checked against the table before any decoding, so a 23 KB PNG that claims
// 60000x60000 costs microseconds, not 14 GB. Independent of the decoding library on purpose.
namespace kiosk::io {

/** @brief The header fields that decide decoding cost and meaning. */
struct ImageHeader {
    ImageFormat format = ImageFormat::Unknown;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    int bitDepth = 0;  ///< bits per sample (PNG 1..16; JPEG precision 8 or 12)
    int channels = 0;  ///< samples per pixel as stored (PNG palette: 1 index)
    bool palette = false;

    /** @brief "16-bit grey PNG", "8-bit RGB JPEG", ... for messages. */
    std::string describe() const;
};

/**
 * @brief Parse the header of a PNG or JPEG in memory; nullopt if `data` is neither or its
 * header is truncated or malformed. Reads at most the bytes up to the first frame header.
 */
std::optional<ImageHeader> peekImageHeader(const std::uint8_t* data, std::size_t size) noexcept;

/** @brief What a tile table holds (docs/store-format.md). */
struct TileExpectation {
    int width = 0;
    int height = 0;
    /// true: elevation / sequence tables (16-bit grey PNG); false: imagery (8-bit PNG or JPEG)
    bool scalar = false;
    /// imagery whose kiosk_layers.description declares RGB (a normal map): 8-bit RGB/RGBA PNG
    bool rgb = false;
};

/** @brief Does a kiosk_layers.description declare a normal map (docs/store-format.md)? */
bool declaresNormalMap(const std::string& description) noexcept;

/** @brief Largest decoded tile accepted, whatever a table claims (the decode byte budget). */
inline constexpr std::uint64_t kMaxTileDecodeBytes = 64ull << 20;

/**
 * @brief Check a stored tile's header against its table before decoding. Errors, with `where`
 * (the tile name) and no file: STORE_TILE_CORRUPT (no readable header), STORE_TILE_FORMAT (wrong
 * format, bit depth or channel count for the table), STORE_TILE_SIZE (dimensions differ from the
 * table's tile size or exceed kMaxTileDecodeBytes).
 */
Diagnostics checkTileHeader(const std::uint8_t* data, std::size_t size,
                            const TileExpectation& expect, const std::string& where);

/**
 * @brief The byte budget every decode passes first, whoever calls it: a PNG or JPEG header
 * that can be read and whose decoded size is at most kMaxTileDecodeBytes; else IMAGE_DECODE
 * with `where`.
 */
Diagnostics checkDecodeBudget(const std::uint8_t* data, std::size_t size, const std::string& where);

}  // namespace kiosk::io
