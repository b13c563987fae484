#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/export/VideoEncoder.h"
#include "runtime/gl/RenderTarget.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief Where `render` puts its frames: one PNG, a folder of numbered PNGs, or a video file.
 * Every kind reads the same RGBA pixels, so a video frame is the PNG frame (exactly, for FFV1).
 * Render thread only; a video is read back straight into the encoder's bounded queue and
 * encoded on its own thread.
 */
class FrameOutput {
public:
    enum class Kind { Png, PngFolder, Video };

    /** @brief Kind of `out` (a trailing '/' or an existing folder is a folder), nullopt if none. */
    static std::optional<Kind> kindOf(const std::string& out);

    static FrameOutput png(std::filesystem::path file);
    static FrameOutput folder(std::filesystem::path dir);
    static Result<FrameOutput> video(const video::VideoOptions& options);

    /** @brief Read the finished frame from `target` and write it (GL current). */
    bool write(const gl::RenderTarget& target, Diagnostics& diags);
    /** @brief Close a video (drain, trailer, chapters); nothing for PNGs. */
    bool finish(Diagnostics& diags);
    Kind kind() const noexcept { return mKind; }

private:
    Kind mKind = Kind::Png;
    std::filesystem::path mPath;
    std::size_t mWritten = 0;
    std::unique_ptr<video::VideoEncoder> mEncoder;
};

}  // namespace kiosk::app
