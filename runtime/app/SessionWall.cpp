// Session on a display wall: overlays in the boxes the wall file places them in.
#include "runtime/app/Session.h"

namespace kiosk::app {

void Session::drawWallOverlays(double time, int width, int height) {
    // Operator messages (notices, layer status) stay on every screen, over the whole output.
    mOverlayOnly = kOverlayStatus;
    drawOverlays(time, width, height);
    const std::pair<const OverlayBox*, unsigned> boxes[] = {
        {&mOverlayLayout->legend, kOverlayLegend},
        {&mOverlayLayout->timeLabel, kOverlayTimeLabel},
        {&mOverlayLayout->title, kOverlayTitle}};
    // Text keeps the size it has on the whole output; only the layout box shrinks.
    mOverlayFontHeight = height;
    for (const auto& [box, bit] : boxes) {
        if (!box->shown) continue;
        const int w = box->w > 0 ? box->w : width, h = box->w > 0 ? box->h : height;
        glViewport(box->x, height - box->y - h, w, h);
        mOverlayOnly = bit;
        mOverlayCorner = box->corner;
        drawOverlays(time, w, h);
    }
    glViewport(0, 0, width, height);
    mOverlayOnly = ~0u;
    mOverlayCorner.reset();
    mOverlayFontHeight = 0;
}

}  // namespace kiosk::app
