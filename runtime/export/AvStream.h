#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/export/StreamModule.h"
#include "runtime/export/VideoEncoder.h"

#include <cstdint>
#include <filesystem>

struct AVFormatContext;
struct AVCodecContext;
struct AVStream;
struct AVFrame;
struct AVPacket;

namespace kiosk::video {

/**
 * @brief One video stream in one file through libavformat/libavcodec: the single place that
 * knows codec names, pixel formats and colour tags (the RGB -> YUV matrix is Yuv420.h). Not
 * thread-safe; the encoder thread owns it. Writes to `path.part` and renames on close(), so a
 * half-written video never carries the final name. Built only into the module geokiosk-av.so
 * (StreamModule.h).
 */
class AvStream final : public EncoderStream {
public:
    AvStream() = default;
    ~AvStream() override;
    AvStream(const AvStream&) = delete;
    AvStream& operator=(const AvStream&) = delete;

    bool open(const VideoOptions& options, Diagnostics& diags) override;
    bool encode(const std::uint8_t* rgba, Diagnostics& diags) override;
    bool close(Diagnostics& diags) override;
    void abandon() override;

private:
    bool drain(bool flushing, Diagnostics& diags);
    void release();
    void error(Diagnostics& diags, const char* code, const std::string& what, int averr);

    VideoOptions mOptions;
    std::filesystem::path mPartPath;
    AVFormatContext* mFormat = nullptr;
    AVCodecContext* mCodec = nullptr;
    AVStream* mStream = nullptr;
    AVFrame* mFrame = nullptr;
    AVPacket* mPacket = nullptr;
    std::int64_t mNextPts = 0;
    bool mHeaderWritten = false;
};

}  // namespace kiosk::video
