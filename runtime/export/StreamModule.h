#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/export/VideoEncoder.h"

#include <cstdint>
#include <memory>

// FFmpeg is loaded only when a video is written. libavcodec/libavformat and what they pull in
// (x264, x265, libvpx, dav1d, librsvg, ... over a hundred libraries, ~20 MB resident) would
// otherwise be mapped into every kiosk process, which never encodes (docs/performance.md). The
// FFmpeg side, AvStream, lives in the module geokiosk-av.so; VideoEncoder drives it through
// this interface.
namespace kiosk::video {

/** @brief One video stream in one file (AvStream in geokiosk-av.so). Not thread-safe. */
class EncoderStream {
public:
    virtual ~EncoderStream() = default;
    virtual bool open(const VideoOptions& options, Diagnostics& diags) = 0;
    /** @brief Convert one RGBA8 frame (bottom row first, glReadPixels' order) and encode it. */
    virtual bool encode(const std::uint8_t* rgba, Diagnostics& diags) = 0;
    /** @brief Flush the codec, write the trailer, move the file into place. */
    virtual bool close(Diagnostics& diags) = 0;
    /** @brief After a failure: release everything and delete the partial file. */
    virtual void abandon() = 0;
};

/** @brief The module's file name and its one exported entry point. */
inline constexpr const char* kAvModuleFile = "geokiosk-av.so";
inline constexpr const char* kAvModuleEntry = "kiosk_video_make_stream";
/** @brief The entry point's type: a new stream, owned by the caller. */
using MakeStreamFn = EncoderStream* (*)();

/**
 * @brief Load geokiosk-av.so (once per process) and make a stream. Looked for beside the
 * executable, then in the installed private library folder relative to it, then in the build
 * folder. Not found or not loadable: EXPORT_MODULE naming the last path tried and why.
 */
std::unique_ptr<EncoderStream> makeEncoderStream(Diagnostics& diags);

}  // namespace kiosk::video
