#include "runtime/app/ImageOutput.h"

#include "runtime/io/FramePng.h"

#include <cstdio>
#include <vector>

namespace kiosk::app {

bool writePng(const std::filesystem::path& path, const gl::Image& image, Diagnostics& diags) {
    const std::filesystem::path tmp = path.string() + ".tmp.png";
    // Written for speed (Sub filter, zlib level 2, two stripes on two threads): it was most of a
    // one-frame render's time at level 6 (docs/performance.md §5.2).
    auto png = io::encodeFramePng(image.rgba.data(), image.width, image.height);
    if (!png) {
        const Diagnostic* e = png.diagnostics.firstError();
        diags.error("OUTPUT_WRITE", path.string(), "",
                    "cannot encode PNG: " + (e ? e->message : std::string("unknown error")));
        return false;
    }
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    const bool written = f && std::fwrite(png->data(), 1, png->size(), f) == png->size();
    const bool closed = f && std::fclose(f) == 0;
    std::error_code ec;
    if (!written || !closed) {
        diags.error("OUTPUT_WRITE", path.string(), "", "cannot write PNG");
        std::filesystem::remove(tmp, ec);
        return false;
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        diags.error("OUTPUT_WRITE", path.string(), "", "cannot rename into place: " + ec.message());
        std::filesystem::remove(tmp, ec);
        return false;
    }
    return true;
}

}  // namespace kiosk::app
