#pragma once

#include <vector>

namespace kiosk::render {

/** @brief Where an overlay panel sits: a corner or the middle of the top / bottom edge. */
enum class Anchor { TopLeft, TopRight, BottomLeft, BottomRight, Top, Bottom };

struct Box {
    float x = 0, y = 0, w = 0, h = 0;
    bool intersects(const Box& o) const noexcept {
        return x < o.x + o.w && o.x < x + w && y < o.y + o.h && o.y < y + h;
    }
};

/**
 * @brief Screen-space placement of overlay panels (title, time label, legend, status lines,
 * chapter captions): each panel goes to its anchor and, if it would cover a panel placed before
 * it, moves away from its edge (down from the top, up from the bottom) until it is clear. So two
 * panels given the same corner stack instead of overdrawing. Pixels, origin top-left. Storage is
 * reused frame to frame (no allocation once warm).
 */
class OverlayLayout {
public:
    /** @brief Start a frame: `margin` pixels from the edges, `gap` pixels between panels. */
    void begin(int width, int height, float margin, float gap);
    /** @brief Place a w x h panel; `margin` < 0 uses the frame's (captions pass the safe area's).
     */
    Box place(Anchor anchor, float w, float h, float margin = -1.0f);

private:
    std::vector<Box> mPlaced;
    float mWidth = 0, mHeight = 0, mMargin = 0, mGap = 0;
};

}  // namespace kiosk::render
