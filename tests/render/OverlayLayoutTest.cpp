#include "runtime/render/OverlayLayout.h"

#include <gtest/gtest.h>

namespace kiosk::render {
namespace {

TEST(OverlayLayout, PanelsGoToTheirAnchors) {
    OverlayLayout l;
    l.begin(800, 600, 12, 8);
    const Box tl = l.place(Anchor::TopLeft, 100, 40);
    EXPECT_FLOAT_EQ(tl.x, 12);
    EXPECT_FLOAT_EQ(tl.y, 12);
    const Box br = l.place(Anchor::BottomRight, 200, 50);
    EXPECT_FLOAT_EQ(br.x, 800 - 12 - 200);
    EXPECT_FLOAT_EQ(br.y, 600 - 12 - 50);
    const Box top = l.place(Anchor::Top, 100, 30);
    EXPECT_FLOAT_EQ(top.x, 350);
    EXPECT_FLOAT_EQ(top.y, 12);
    const Box bl = l.place(Anchor::BottomLeft, 50, 20, 30);  // own (safe-area) margin
    EXPECT_FLOAT_EQ(bl.x, 30);
    EXPECT_FLOAT_EQ(bl.y, 600 - 30 - 20);
}

TEST(OverlayLayout, PanelsSharingAnEdgeStackInsteadOfOverlapping) {
    OverlayLayout l;
    l.begin(400, 300, 12, 8);
    const Box a = l.place(Anchor::TopRight, 250, 40);
    const Box b = l.place(Anchor::TopLeft, 250, 40);  // would cover a: goes below it
    EXPECT_FALSE(a.intersects(b));
    EXPECT_FLOAT_EQ(b.y, a.y + a.h + 8);
    const Box c = l.place(Anchor::BottomLeft, 100, 20);
    const Box d = l.place(Anchor::BottomLeft, 100, 20);  // a second status line: above the first
    EXPECT_FLOAT_EQ(d.y, c.y - 8 - 20);
    // A wide caption at the bottom clears both status lines.
    const Box e = l.place(Anchor::Bottom, 300, 30);
    EXPECT_FALSE(e.intersects(c));
    EXPECT_FALSE(e.intersects(d));
    EXPECT_LT(e.y + e.h, d.y);
}

}  // namespace
}  // namespace kiosk::render
