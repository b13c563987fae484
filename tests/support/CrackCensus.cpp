#include "tests/support/CrackCensus.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace kiosk::test {
namespace {

bool near(const std::uint8_t* p, int r, int g, int b, int tol) {
    return std::abs(p[0] - r) <= tol && std::abs(p[1] - g) <= tol && std::abs(p[2] - b) <= tol;
}

/** 8-connected flood fill of `passable` from every set `seed`, into `reached`. */
void flood(int w, int h, const std::vector<std::uint8_t>& passable, std::vector<std::uint8_t>& seed,
           std::vector<std::uint8_t>& reached) {
    std::vector<int> stack;
    for (int i = 0; i < w * h; ++i)
        if (seed[std::size_t(i)] && passable[std::size_t(i)] && !reached[std::size_t(i)]) {
            reached[std::size_t(i)] = 1;
            stack.push_back(i);
        }
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        const int x = i % w, y = i / w;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                const std::size_t n = std::size_t(ny) * std::size_t(w) + std::size_t(nx);
                if (passable[n] && !reached[n]) {
                    reached[n] = 1;
                    stack.push_back(int(n));
                }
            }
    }
}

}  // namespace

CrackCount crackPixels(const gl::Image& img) {
    const int w = img.width, h = img.height;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    std::vector<std::uint8_t> sky(n), panel(n), passable(n), seed(n), reached(n);
    CrackCount c;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
            sky[i] = near(img.pixel(x, y), 158, 181, 204, 2);
            panel[i] = near(img.pixel(x, y), 53, 63, 76, 3);
            c.sky += sky[i];
        }
    passable = sky;
    auto openBox = [&](int y0, int y1, int x0, int x1) {
        for (int y = std::max(y0, 0); y < std::min(y1, h); ++y)
            for (int x = std::max(x0, 0); x < std::min(x1, w); ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
                passable[i] = seed[i] = 1;
            }
    };
    for (int x = 0; x < w; ++x)
        seed[std::size_t(x)] = seed[std::size_t(h - 1) * std::size_t(w) + std::size_t(x)] = 1;
    for (int y = 0; y < h; ++y)
        seed[std::size_t(y) * std::size_t(w)] =
            seed[std::size_t(y) * std::size_t(w) + std::size_t(w - 1)] = 1;
    // Panels: bounding boxes of panel-colour blobs of at least 100 px, grown by 3 px.
    std::vector<std::uint8_t> labelled(n, 0);
    std::vector<int> stack;
    for (std::size_t i = 0; i < n; ++i) {
        if (!panel[i] || labelled[i]) continue;
        int count = 0, y0 = h, y1 = 0, x0 = w, x1 = 0;
        labelled[i] = 1;
        stack.assign(1, int(i));
        while (!stack.empty()) {
            const int j = stack.back();
            stack.pop_back();
            const int x = j % w, y = j / w;
            ++count;
            y0 = std::min(y0, y), y1 = std::max(y1, y + 1), x0 = std::min(x0, x),
            x1 = std::max(x1, x + 1);
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                    const std::size_t k = std::size_t(ny) * std::size_t(w) + std::size_t(nx);
                    if (panel[k] && !labelled[k]) {
                        labelled[k] = 1;
                        stack.push_back(int(k));
                    }
                }
        }
        if (count >= 100) openBox(y0 - 3, y1 + 3, x0 - 3, x1 + 3);
    }
    openBox(h - 12, h - 4, 10, w - 10);  // progress bar band
    flood(w, h, passable, seed, reached);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
            if (sky[i] && !reached[i] && c.cracks++ == 0) c.firstX = x, c.firstY = y;
        }
    return c;
}

}  // namespace kiosk::test
