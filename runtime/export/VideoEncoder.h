#pragma once

#include "runtime/core/Result.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

// Video export through FFmpeg's libraries (libavcodec, libavformat, libavutil). No GL here: the
// frame loop hands finished RGBA readbacks (the very bytes the PNG path writes) to the encoder.
namespace kiosk::video {

/** @brief What a file name's extension selects. */
enum class VideoFormat {
    H264Mp4,  ///< .mp4: H.264 (libx264) yuv420p, BT.709 limited range, CRF
    Ffv1Mkv,  ///< .mkv: FFV1 lossless RGB (0RGB32): decoded frames equal the input exactly
    Vp9Webm,  ///< .webm: VP9 (libvpx) yuv420p, BT.709 limited range, CRF
};

/** @brief .mp4 / .mkv / .webm (case-sensitive, like the rest of the CLI), else nullopt. */
std::optional<VideoFormat> videoFormatForPath(const std::filesystem::path& path);
const char* videoFormatName(VideoFormat f) noexcept;

/** @brief A named span of the video (MP4 / Matroska chapter markers). Seconds of video time. */
struct VideoChapter {
    std::string title;
    double start = 0;
    double end = 0;
};

/**
 * @brief How much higher (lower priority) the nice value of the encoder thread, and of the
 * threads the codec starts from it, is than the caller's, so that encoding yields the cores to
 * the rasterizer threads the render thread waits for. On the 2-core benchmark machine the
 * difference against the same priority was within the run-to-run noise (docs/performance.md
 * §7). Capped at 19.
 */
inline constexpr int kEncoderNice = 10;
/** @brief The encoder thread's name (/proc/PID/task/TID/comm), for tools and the tests. */
inline constexpr const char* kEncoderThreadName = "kiosk-encode";

struct VideoOptions {
    std::filesystem::path path;
    VideoFormat format = VideoFormat::H264Mp4;
    int width = 0;   ///< even for the 4:2:0 formats
    int height = 0;  ///< even for the 4:2:0 formats
    double fps = 30;
    /** @brief Constant rate factor; nullopt: the format's default (H.264 18, VP9 31). Ignored by
     * FFV1. */
    std::optional<int> crf;
    /** @brief libx264 preset (H.264 only); empty: defaultPreset(). */
    std::string preset;
    std::vector<VideoChapter> chapters;
    /** @brief Nice steps of the encoder's threads below the caller (kEncoderNice; 0: same). */
    int encoderNice = kEncoderNice;
    /** @brief Frames that may wait for the encoder thread before acquire() blocks. */
    int queueFrames = 4;
};

/** @brief Default CRF of a lossy format (what `--crf` overrides). */
int defaultCrf(VideoFormat f) noexcept;
/** @brief The libx264 preset used when `--preset` is not given. */
const char* defaultPreset() noexcept;
/** @brief Whether @p name is one of libx264's presets (ultrafast .. veryslow). */
bool isX264Preset(std::string_view name) noexcept;
/** @brief The presets isX264Preset() accepts, fastest first, comma-separated (for messages). */
std::string x264PresetNames();
/** @brief Valid `--crf` range of a lossy format (libx264 0..51, libvpx-vp9 0..63). */
int maxCrf(VideoFormat f) noexcept;

/**
 * @brief Encodes RGBA8 frames into a video file on its own thread. Frames are bottom row first,
 * as glReadPixels writes them: the encoder thread reads the rows upwards while converting, so
 * the render thread reads back straight into the queue and neither flips nor copies.
 *
 * acquire() hands out one of a fixed pool of frame buffers (bounded memory: queueFrames frames)
 * for the caller to fill (the readback writes straight into it) and submit() queues it, so
 * rendering the next frame overlaps encoding this one. finish() drains the queue, flushes the codec
 * and writes the trailer (and the chapters). Errors (disk full, codec failure) surface at the next
 * acquire() or at finish(). Codes: EXPORT_MODULE (the FFmpeg module geokiosk-av.so cannot be
 * loaded; StreamModule.h), EXPORT_CODEC (encoder missing from this FFmpeg build), EXPORT_OPEN,
 * EXPORT_ENCODE, EXPORT_WRITE.
 */
class VideoEncoder {
public:
    static Result<std::unique_ptr<VideoEncoder>> open(const VideoOptions& options);
    ~VideoEncoder();
    VideoEncoder(const VideoEncoder&) = delete;
    VideoEncoder& operator=(const VideoEncoder&) = delete;

    /** @brief A free frame buffer (width*height*4 bytes) to fill, waiting while the encoder is
     * queueFrames behind; null once encoding failed (the reason appended to `diags`). */
    std::uint8_t* acquire(Diagnostics& diags);
    /** @brief Queue the buffer the last acquire() returned, filled. */
    void submit();
    /** @brief Encode what is queued, flush and close the file. Call once. */
    bool finish(Diagnostics& diags);

    std::int64_t framesEncoded() const noexcept;

    struct Impl;

private:
    explicit VideoEncoder(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> mImpl;
};

}  // namespace kiosk::video
