#include "runtime/topo/RasterView.h"

#include <algorithm>
#include <cmath>

namespace kiosk::topo {

RasterView RasterView::window(const float* dem, int demWidth, int demHeight, std::ptrdiff_t stride,
                              int x0, int y0, int w, int h, double pixelSizeX, double pixelSizeY,
                              int maxApron) noexcept {
    RasterView v;
    v.pixelSizeX = pixelSizeX;
    v.pixelSizeY = pixelSizeY;
    v.stride = stride;
    // Clip in 64 bits so huge x0 + w cannot overflow.
    const long long x1 = std::min<long long>(static_cast<long long>(x0) + w, demWidth);
    const long long y1 = std::min<long long>(static_cast<long long>(y0) + h, demHeight);
    const int cx0 = std::max(x0, 0);
    const int cy0 = std::max(y0, 0);
    if (dem == nullptr || x1 <= cx0 || y1 <= cy0) return v;
    v.width = static_cast<int>(x1 - cx0);
    v.height = static_cast<int>(y1 - cy0);
    v.data = dem + static_cast<std::ptrdiff_t>(cy0) * stride + cx0;
    maxApron = std::max(maxApron, 0);
    v.apronLeft = std::min(cx0, maxApron);
    v.apronTop = std::min(cy0, maxApron);
    v.apronRight = static_cast<int>(std::min<long long>(demWidth - x1, maxApron));
    v.apronBottom = static_cast<int>(std::min<long long>(demHeight - y1, maxApron));
    return v;
}

Diagnostics RasterView::validate(const std::string& where) const {
    Diagnostics d;
    const char* code = "TOPO_INVALID_VIEW";
    if (data == nullptr) d.error(code, "", where, "elevation view has no data (null pointer)");
    if (width <= 0 || height <= 0)
        d.error(code, "", where,
                "elevation view is empty (" + std::to_string(width) + " x " +
                    std::to_string(height) + ")");
    if (apronLeft < 0 || apronTop < 0 || apronRight < 0 || apronBottom < 0)
        d.error(code, "", where, "elevation view has a negative apron");
    else if (width > 0 && stride < static_cast<std::ptrdiff_t>(apronLeft) + width + apronRight)
        d.error(code, "", where,
                "elevation view stride " + std::to_string(stride) +
                    " is smaller than apronLeft + width + apronRight = " +
                    std::to_string(static_cast<long long>(apronLeft) + width + apronRight));
    if (!(std::isfinite(pixelSizeX) && pixelSizeX > 0.0) ||
        !(std::isfinite(pixelSizeY) && pixelSizeY > 0.0))
        d.error(code, "", where,
                "pixel size must be finite and > 0 (got " + std::to_string(pixelSizeX) + " x " +
                    std::to_string(pixelSizeY) + ")");
    return d;
}

}  // namespace kiosk::topo
