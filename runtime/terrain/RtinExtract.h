#pragma once

#include <algorithm>
#include <cstdlib>

namespace kiosk::terrain {

/**
 * @brief The top-down RTIN extraction shared by RtinMesher (split errors from the posts) and
 * StoredMeshBuilder (split tiers from the store), so both emit the same triangles in the same
 * order. (a, b) is the hypotenuse, c the right angle (post coordinates). A triangle is split at
 * its hypotenuse midpoint while its legs are longer than one post and it is larger than one cell
 * of `cellPosts` (always: the mesh stays conforming and each triangle belongs to one cell) or
 * `split(mx, my)` says so; otherwise `emit(ax, ay, bx, by, cx, cy)`.
 */
template <class Split, class Emit>
void rtinExtract(int ax, int ay, int bx, int by, int cx, int cy, int cellPosts, const Split& split,
                 const Emit& emit) {
    const int mx = (ax + bx) / 2, my = (ay + by) / 2;
    const int spanX = std::max({ax, bx, cx}) - std::min({ax, bx, cx});
    const int spanY = std::max({ay, by, cy}) - std::min({ay, by, cy});
    const bool largerThanCell = spanX > cellPosts || spanY > cellPosts;
    if (std::abs(ax - cx) + std::abs(ay - cy) > 1 && (largerThanCell || split(mx, my))) {
        rtinExtract(ax, ay, cx, cy, mx, my, cellPosts, split, emit);
        rtinExtract(cx, cy, bx, by, mx, my, cellPosts, split, emit);
        return;
    }
    emit(ax, ay, bx, by, cx, cy);
}

}  // namespace kiosk::terrain
