#include "runtime/anim/ArrivalThresholds.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kiosk::anim {
namespace {

// "No source" stand-in for +infinity: large enough never to win, finite so the parabola
// intersections below stay well defined.
constexpr double kFar = 1e20;

// 1-D squared distance transform of sampled function f (Felzenszwalb & Huttenlocher 2012).
void edt1d(const double* f, int n, double* d, int* v, double* z) {
    int k = 0;
    v[0] = 0;
    z[0] = -std::numeric_limits<double>::infinity();
    z[1] = std::numeric_limits<double>::infinity();
    auto intersect = [&](int q, int p) {
        return ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p));
    };
    for (int q = 1; q < n; ++q) {
        double s = intersect(q, v[k]);
        // z[0] is -inf and s is finite (f <= kFar), so this stops at k == 0 at the latest.
        while (s <= z[k]) {
            --k;
            s = intersect(q, v[k]);
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = std::numeric_limits<double>::infinity();
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < q) ++k;
        const double dq = q - v[k];
        d[q] = dq * dq + f[v[k]];
    }
}

// Squared Euclidean distance to the nearest `source` pixel, kFar-ish where there is none.
void edt2d(const std::vector<unsigned char>& source, int w, int h, std::vector<double>& out) {
    const auto size = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    out.assign(size, kFar);
    for (std::size_t i = 0; i < size; ++i)
        if (source[i]) out[i] = 0.0;
    const int n = std::max(w, h);
    std::vector<double> f(static_cast<std::size_t>(n)), d(static_cast<std::size_t>(n)),
        z(static_cast<std::size_t>(n) + 1);
    std::vector<int> v(static_cast<std::size_t>(n));
    for (int x = 0; x < w; ++x) {
        for (int y = 0; y < h; ++y)
            f[std::size_t(y)] = out[std::size_t(y) * std::size_t(w) + std::size_t(x)];
        edt1d(f.data(), h, d.data(), v.data(), z.data());
        for (int y = 0; y < h; ++y)
            out[std::size_t(y) * std::size_t(w) + std::size_t(x)] = d[std::size_t(y)];
    }
    for (int y = 0; y < h; ++y) {
        double* row = out.data() + std::size_t(y) * std::size_t(w);
        std::copy(row, row + w, f.begin());
        edt1d(f.data(), w, d.data(), v.data(), z.data());
        std::copy(d.begin(), d.begin() + w, row);
    }
}

bool sameClass(float a, float b) {
    return a == b || (std::isnan(a) && std::isnan(b));
}

}  // namespace

void computeArrivalThresholds(std::span<const float> v0, std::span<const float> v1, int width,
                              int height, std::optional<float> nodataAs, std::vector<float>& out) {
    out.clear();
    if (width <= 0 || height <= 0) return;
    const auto size = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (v0.size() != size || v1.size() != size) return;
    auto cls0 = [&](std::size_t i) { return std::isnan(v0[i]) && nodataAs ? *nodataAs : v0[i]; };
    auto cls1 = [&](std::size_t i) { return std::isnan(v1[i]) && nodataAs ? *nodataAs : v1[i]; };
    out.assign(size, 0.0f);

    std::vector<unsigned char> done(size, 0), source(size);
    std::vector<double> dist0, dist1;
    for (std::size_t seed = 0; seed < size; ++seed) {
        if (done[seed] || sameClass(cls0(seed), cls1(seed))) continue;
        // One pass per class c that pixels change into.
        const float c = cls1(seed);
        bool anySource = false;
        for (std::size_t i = 0; i < size; ++i) {
            source[i] = sameClass(cls0(i), c);
            anySource = anySource || source[i];
        }
        edt2d(source, width, height, dist0);
        // Beyond the new front: not c in frame 1 and not c in frame 0 either (pixels that left
        // class c, e.g. burning -> burned, lie behind the front and must not attract it).
        for (std::size_t i = 0; i < size; ++i)
            source[i] = !sameClass(cls1(i), c) && !sameClass(cls0(i), c);
        edt2d(source, width, height, dist1);
        double maxD0 = 0.0, maxD1 = 0.0;
        for (std::size_t i = seed; i < size; ++i) {
            if (sameClass(cls0(i), cls1(i)) || !sameClass(cls1(i), c)) continue;
            if (dist0[i] < kFar * 0.5) maxD0 = std::max(maxD0, std::sqrt(dist0[i]));
            if (dist1[i] < kFar * 0.5) maxD1 = std::max(maxD1, std::sqrt(dist1[i]));
        }
        for (std::size_t i = seed; i < size; ++i) {
            if (done[i] || sameClass(cls0(i), cls1(i)) || !sameClass(cls1(i), c)) continue;
            done[i] = 1;
            const bool has0 = anySource && dist0[i] < kFar * 0.5;
            const bool has1 = dist1[i] < kFar * 0.5;
            const double d0 = has0 ? std::sqrt(dist0[i]) : 0.0;
            const double d1 = has1 ? std::sqrt(dist1[i]) : 0.0;
            double th;
            if (has0 && has1)
                th = d0 / (d0 + d1);
            else if (has1)
                th = 1.0 - d1 / (maxD1 + 1.0);
            else if (has0)
                th = d0 / (maxD0 + 1.0);  // the patch fills the raster: sweep outwards from d0
            else
                th = 0.5;
            out[i] = static_cast<float>(std::clamp(th, 0.0, 1.0));
        }
    }
}

}  // namespace kiosk::anim
