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
    // H.264: 18 with the ultrafast preset keeps the PSNR that veryfast at 15 gave (the demo at
    // 1080p and 480x270, docs/cli.md), which keeps the overlays' text and the legend's thin ticks
    // clean; VP9's scale differs, 31 is libvpx's recommended 1080p quality.
    return f == VideoFormat::Vp9Webm ? 31 : 18;
}

const char* defaultPreset() noexcept {
    // llvmpipe keeps both cores busy drawing, so the encoder's CPU time is the export's cost:
    // bench-export measured ultrafast at 6-12 % of the 1080p frame and veryfast at 27-34 % (files
    // about 3x smaller); the goal is < 10 %. Smaller files: `--preset veryfast`.
    return "ultrafast";
}

namespace {
constexpr std::string_view kX264Presets[] = {
    "ultrafast", "superfast", "veryfast", "faster", "fast", "medium", "slow", "slower", "veryslow"};
}  // namespace

bool isX264Preset(std::string_view name) noexcept {
    for (auto p : kX264Presets)
        if (p == name) return true;
    return false;
}

std::string x264PresetNames() {
    std::string names;
    for (auto p : kX264Presets) names += (names.empty() ? "" : ", ") + std::string(p);
    return names;
}

int maxCrf(VideoFormat f) noexcept {
    return f == VideoFormat::Vp9Webm ? 63 : 51;
}

}  // namespace kiosk::video
