#pragma once

#include <filesystem>

#include "runtime/core/Diagnostics.h"
#include "runtime/gl/RenderTarget.h"

namespace kiosk::app {

/**
 * @brief Write an RGBA8 image as PNG (alpha dropped: frames are opaque). Writes to a temporary
 * file in the same folder and renames, so a reader (a video encoder, a kiosk preview) never
 * sees a half-written frame.
 */
bool writePng(const std::filesystem::path& path, const gl::Image& image, Diagnostics& diags);

}  // namespace kiosk::app
