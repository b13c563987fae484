#include "runtime/app/ImageOutput.h"

#include <OpenImageIO/imageio.h>

#include <vector>

namespace kiosk::app {

bool writePng(const std::filesystem::path& path, const gl::Image& image, Diagnostics& diags) {
    const std::filesystem::path tmp = path.string() + ".tmp.png";
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out) {
        diags.error("OUTPUT_WRITE", path.string(), "", "cannot create PNG writer: " + OIIO::geterror());
        return false;
    }
    std::vector<std::uint8_t> rgb(std::size_t(image.width) * std::size_t(image.height) * 3);
    for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
        rgb[i * 3 + 0] = image.rgba[i * 4 + 0];
        rgb[i * 3 + 1] = image.rgba[i * 4 + 1];
        rgb[i * 3 + 2] = image.rgba[i * 4 + 2];
    }
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Software", "geokiosk");
    if (!out->open(tmp.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) ||
        !out->close()) {
        diags.error("OUTPUT_WRITE", path.string(), "", "cannot write PNG: " + out->geterror());
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        return false;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        diags.error("OUTPUT_WRITE", path.string(), "", "cannot rename into place: " + ec.message());
        std::filesystem::remove(tmp, ec);
        return false;
    }
    return true;
}

}  // namespace kiosk::app
