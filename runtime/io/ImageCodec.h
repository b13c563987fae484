#pragma once

#include "runtime/core/Result.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kiosk::io {

/** @brief Container format of an encoded tile, recognised from its magic bytes. */
enum class ImageFormat { Unknown, Png, Jpeg, Tiff };

ImageFormat sniffImageFormat(const std::uint8_t* data, std::size_t size) noexcept;

/** @brief A decoded image: 8- or 16-bit samples, interleaved channels. */
struct DecodedImage {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<std::uint16_t> samples16;  ///< filled by decodeGray16
    std::vector<std::uint8_t> samples8;    ///< filled by decodeRgba8 (always 4 channels)
};

/**
 * @brief In-memory image codecs: PNG through libspng, JPEG through libjpeg-turbo (TurboJPEG), no
 * temporary files. TIFF is recognised by sniffImageFormat but not decoded (GeoPackage tiles are
 * PNG or JPEG). Thread-safe: every call owns its encoder/decoder. Never throws; errors carry code
 * IMAGE_ENCODE / IMAGE_DECODE and `where` (the caller's tile name).
 */
Result<std::vector<std::uint8_t>> encodePng16(const std::uint16_t* gray, int width, int height,
                                              int compressionLevel);
/** @brief 8-bit PNG with 1..4 channels. */
Result<std::vector<std::uint8_t>> encodePng8(const std::uint8_t* pixels, int width, int height,
                                             int channels, int compressionLevel);
/** @brief Baseline JPEG, RGB (3 channels). */
Result<std::vector<std::uint8_t>> encodeJpeg(const std::uint8_t* rgb, int width, int height,
                                             int quality);

/** @brief Single-channel 16-bit PNG (other bit depths are converted). */
Result<DecodedImage> decodeGray16(const std::uint8_t* data, std::size_t size,
                                  const std::string& where);
/** @brief PNG or JPEG of any channel count, expanded to RGBA8 (gray -> grey, alpha = 255). */
Result<DecodedImage> decodeRgba8(const std::uint8_t* data, std::size_t size,
                                 const std::string& where);

}  // namespace kiosk::io
