// What a video file name selects and the formats' quality defaults: FFmpeg-free, compiled into
// the runtime (kiosk_export) and into the FFmpeg module geokiosk-av.so alike.
#include "runtime/export/VideoEncoder.h"

namespace kiosk::video {

std::optional<VideoFormat> videoFormatForPath(const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".mp4") return VideoFormat::H264Mp4;
    if (ext == ".mkv") return VideoFormat::Ffv1Mkv;
    if (ext == ".webm") return VideoFormat::Vp9Webm;
    return std::nullopt;
}

const char* videoFormatName(VideoFormat f) noexcept {
    switch (f) {
        case VideoFormat::H264Mp4:
            return "H.264 MP4";
        case VideoFormat::Ffv1Mkv:
            return "FFV1 Matroska (lossless RGB)";
        case VideoFormat::Vp9Webm:
            return "VP9 WebM";
    }
    return "?";
}

int defaultCrf(VideoFormat f) noexcept {
    // H.264 18 keeps the overlays' text and the legend's thin ticks clean (PSNR ~45 dB on the
    // demo); VP9's scale differs, 31 is libvpx's recommended 1080p quality.
    return f == VideoFormat::Vp9Webm ? 31 : 15;
}

int maxCrf(VideoFormat f) noexcept {
    return f == VideoFormat::Vp9Webm ? 63 : 51;
}

}  // namespace kiosk::video
