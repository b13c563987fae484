#include "runtime/render/OverlayLayout.h"

#include <algorithm>

namespace kiosk::render {

void OverlayLayout::begin(int width, int height, float margin, float gap) {
    mPlaced.clear();
    mWidth = float(width);
    mHeight = float(height);
    mMargin = margin;
    mGap = gap;
}

Box OverlayLayout::place(Anchor anchor, float w, float h, float margin) {
    const float m = margin < 0 ? mMargin : margin;
    Box b{0, 0, w, h};
    switch (anchor) {
        case Anchor::TopLeft:
        case Anchor::BottomLeft:
            b.x = m;
            break;
        case Anchor::TopRight:
        case Anchor::BottomRight:
            b.x = mWidth - m - w;
            break;
        case Anchor::Top:
        case Anchor::Bottom:
            b.x = (mWidth - w) * 0.5f;
            break;
    }
    b.x =
        std::max(b.x, std::min(m, (mWidth - w) * 0.5f));  // too wide: keep the left edge on screen
    const bool fromTop =
        anchor == Anchor::TopLeft || anchor == Anchor::TopRight || anchor == Anchor::Top;
    b.y = fromTop ? m : mHeight - m - h;
    // Each pass moves past one panel in the way; every panel is passed at most once.
    for (std::size_t pass = 0; pass <= mPlaced.size(); ++pass) {
        const Box grown{b.x - mGap, b.y - mGap, b.w + 2 * mGap, b.h + 2 * mGap};
        const auto hit = std::find_if(mPlaced.begin(), mPlaced.end(),
                                      [&](const Box& o) { return grown.intersects(o); });
        if (hit == mPlaced.end()) break;
        b.y = fromTop ? hit->y + hit->h + mGap : hit->y - mGap - h;
    }
    mPlaced.push_back(b);
    return b;
}

}  // namespace kiosk::render
