#pragma once

#include "runtime/core/Result.h"

#include <cstdint>
#include <vector>

namespace kiosk::io {

/**
 * @brief A rendered RGBA frame as an 8-bit RGB PNG (alpha dropped), written for speed: the Sub
 * filter on every row, zlib level 2, and the rows deflated as two stripes on two threads (the
 * second with the first's last 32 KiB as its dictionary; one zlib stream, as pigz joins them). A
 * 1920x1080 frame took 0.07-0.08 s on one thread; the bytes depend only on the pixels, and any
 * PNG decoder reads the same pixels (docs/performance.md §5.2). Errors: IMAGE_ENCODE.
 */
Result<std::vector<std::uint8_t>> encodeFramePng(const std::uint8_t* rgba, int width, int height);

}  // namespace kiosk::io
