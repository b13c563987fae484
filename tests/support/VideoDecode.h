#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace kiosk::test {

/** @brief A video decoded with libavcodec into RGB8 frames, plus what its stream declares. */
struct DecodedVideo {
    std::string error;  ///< empty on success
    std::string codec;  ///< "h264", "ffv1", "vp9"
    int width = 0, height = 0;
    double fps = 0;
    int colorPrimaries = 0, colorTrc = 0, colorSpace = 0, colorRange = 0;  ///< AVCOL_* values
    std::vector<std::vector<std::uint8_t>> frames;                         ///< RGB8, top row first
};

/**
 * @brief Decode every frame. YUV is turned back into RGB with the matrix and range the stream
 * declares (so a wrong tag shows up as wrong colours); RGB formats are repacked exactly.
 */
DecodedVideo decodeVideo(const std::filesystem::path& file);

/** @brief PSNR (dB) of RGB8 `b` against `a` over all frames (MSE averaged over the clip). */
double clipPsnr(const std::vector<std::vector<std::uint8_t>>& a,
                const std::vector<std::vector<std::uint8_t>>& b);

}  // namespace kiosk::test
