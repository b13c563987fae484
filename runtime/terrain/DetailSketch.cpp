#include "runtime/terrain/DetailSketch.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kiosk::terrain {
namespace {

/** Half-size of the detail region in eye heights above the ground. */
constexpr double kRangeFactor = 6.0;
constexpr double kMinPosts = 4.0, kMaxPosts = 128.0;
constexpr float kVisibleFloor = 0.2f;

double bilinear(const DetailSketch& s, const std::vector<float>& v, const glm::dvec2& p) {
    if (s.width < 2 || s.height < 2 || v.size() < std::size_t(s.width) * std::size_t(s.height))
        return std::numeric_limits<double>::quiet_NaN();
    const glm::dvec2 u = (p - s.min) / s.spacing;
    const double fx = std::clamp(u.x, 0.0, double(s.width - 1)),
                 fy = std::clamp(u.y, 0.0, double(s.height - 1));
    const int x0 = std::min(int(fx), s.width - 2), y0 = std::min(int(fy), s.height - 2);
    const double ax = fx - x0, ay = fy - y0;
    const auto at = [&](int x, int y) { return double(v[s.index(x, y)]); };
    return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) +
           ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
}

}  // namespace

double DetailSketch::heightAt(const glm::dvec2& p) const {
    return bilinear(*this, heights, p);
}

double DetailSketch::amplitudeAt(const glm::dvec2& p) const {
    const double a = bilinear(*this, amplitude, p);
    return std::isfinite(a) ? a : 0.0;
}

glm::dvec3 DetailSketch::normalAt(const glm::dvec2& p) const {
    if (width >= 2 && height >= 2 && normals.size() >= std::size_t(width) * std::size_t(height)) {
        const glm::dvec2 u =
            glm::clamp((p - min) / spacing, glm::dvec2(0.0), glm::dvec2(width - 1, height - 1));
        const int x0 = std::min(int(u.x), width - 2), y0 = std::min(int(u.y), height - 2);
        const double ax = u.x - x0, ay = u.y - y0;
        const auto n = [&](int x, int y) { return glm::dvec3(normals[index(x, y)]); };
        const glm::dvec3 v = (1 - ay) * ((1 - ax) * n(x0, y0) + ax * n(x0 + 1, y0)) +
                             ay * ((1 - ax) * n(x0, y0 + 1) + ax * n(x0 + 1, y0 + 1));
        if (glm::length(v) > 1e-9) return glm::normalize(v);
    }
    const double e = spacing;
    const double dx = heightAt(p + glm::dvec2(e, 0)) - heightAt(p - glm::dvec2(e, 0));
    const double dy = heightAt(p + glm::dvec2(0, e)) - heightAt(p - glm::dvec2(0, e));
    if (!std::isfinite(dx) || !std::isfinite(dy)) return {0.0, 0.0, 1.0};
    return glm::normalize(glm::dvec3(-dx / (2 * e), -dy / (2 * e), 1.0));
}

bool fillFromNearest(std::vector<float>& h, std::vector<glm::vec3>& n, int width, int height,
                     std::vector<std::uint32_t>& queue) {
    queue.clear();
    for (std::size_t k = 0; k < h.size(); ++k)
        if (std::isfinite(h[k])) queue.push_back(std::uint32_t(k));
    if (queue.empty()) return false;
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::uint32_t k = queue[head];
        const int x = int(k % std::uint32_t(width)), y = int(k / std::uint32_t(width));
        const int d[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        for (const auto& o : d) {
            const int nx = x + o[0], ny = y + o[1];
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            const std::size_t q = std::size_t(ny) * std::size_t(width) + std::size_t(nx);
            if (std::isfinite(h[q])) continue;
            h[q] = h[k];
            if (q < n.size() && k < n.size()) n[q] = n[k];
            queue.push_back(std::uint32_t(q));
        }
    }
    return true;
}

void computeDetailAmplitude(DetailSketch& s) {
    const std::size_t count = std::size_t(s.width) * std::size_t(s.height);
    s.amplitude.assign(count, 0.0f);
    if (s.heights.size() < count || s.cap.size() < count) return;
    for (int j = 0; j < s.height; ++j)
        for (int i = 0; i < s.width; ++i) {
            const float z = s.heights[s.index(i, j)];
            if (!std::isfinite(z)) continue;
            double sum = 0.0;
            int n = 0;
            const int d[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            for (const auto& o : d) {
                const int x = i + o[0], y = j + o[1];
                if (x < 0 || y < 0 || x >= s.width || y >= s.height) continue;
                const float zn = s.heights[s.index(x, y)];
                if (!std::isfinite(zn)) continue;
                sum += zn;
                ++n;
            }
            // Post-scale relief: how far the post stands out of its neighbours' mean.
            const double rough = n ? std::fabs(double(z) - sum / n) : 0.0;
            s.amplitude[s.index(i, j)] = float(std::clamp(
                kDetailRoughnessGain * rough, 0.0, double(std::max(0.0f, s.cap[s.index(i, j)]))));
        }
}

DetailRegion planDetailRegion(const math::Camera& cam, double groundZ, double d0,
                              const glm::dvec2& origin, const glm::dvec2& dataMin,
                              const glm::dvec2& dataMax, double rangeScale) {
    DetailRegion r;
    if (!(d0 > 0.0)) return r;
    const double above = std::max(cam.eye.z - groundZ, d0);
    const double half =
        std::clamp(kRangeFactor * above * rangeScale, kMinPosts * d0, kMaxPosts * d0);
    glm::dvec2 centre(cam.eye);
    const glm::dvec2 fwd(cam.forward);
    // Ahead of the nadir: behind the camera the importance is low anyway (S_f), so the region's
    // samples go where the view is.
    if (glm::length(fwd) > 1e-6) centre += glm::normalize(fwd) * (0.6 * half);
    const auto snapDown = [&](glm::dvec2 p) { return origin + glm::floor((p - origin) / d0) * d0; };
    const auto snapUp = [&](glm::dvec2 p) { return origin + glm::ceil((p - origin) / d0) * d0; };
    r.min = glm::max(snapDown(centre - half), snapUp(dataMin));
    r.max = glm::min(snapUp(centre + half), snapDown(dataMax));
    if (r.max.x - r.min.x < kMinPosts * d0 - 1e-6 || r.max.y - r.min.y < kMinPosts * d0 - 1e-6)
        return {};
    return r;
}

double maxVisibleGridSpacing(const WarpGrid& g, const DetailSketch& sk, const math::Camera& cam) {
    const glm::dmat4 viewProj = cam.projection() * cam.view();
    double m = 0.0;
    for (int t = 0; t < g.n; ++t)
        for (int s = 0; s < g.n; ++s) {
            const glm::dvec2 p = g.at(s, t);
            const double z = sk.heightAt(p);
            const glm::dvec4 c = viewProj * glm::dvec4(p, std::isfinite(z) ? z : 0.0, 1.0);
            if (c.w <= 0.0 || std::fabs(c.x) > 1.05 * c.w || std::fabs(c.y) > 1.05 * c.w) continue;
            m = std::max(m, maxNeighbourDistance(g, s, t));
        }
    return m;
}

ImportanceMap viewImportance(const DetailSketch& sketch, const math::Camera& cam, double cellPx,
                             int size) {
    ImportanceMap m;
    m.min = sketch.min;
    m.max = sketch.max();
    m.size = std::max(size, 2);
    m.values.assign(std::size_t(m.size) * std::size_t(m.size), 0.0f);
    const double focal = cam.viewportHeight / (2.0 * std::tan(glm::radians(cam.fovYDeg) * 0.5));
    const glm::dmat4 viewProj = cam.projection() * cam.view();
    const double d0 = sketch.spacing;
    // Weight of the first octave in the normalised sum of kDetailOctaves halving octaves.
    const double w1 = 1.0 / (2.0 - std::ldexp(1.0, 1 - kDetailOctaves));
    float peak = 0.0f;
    std::vector<float> visible(m.values.size(), 0.0f);
    for (int j = 0; j < m.size; ++j)
        for (int i = 0; i < m.size; ++i) {
            const glm::dvec2 p = m.min + (m.max - m.min) * glm::dvec2(i, j) / double(m.size - 1);
            double z = sketch.heightAt(p);
            if (!std::isfinite(z)) z = cam.eye.z;
            const glm::dvec3 P(p, z);
            const double d = std::max(glm::distance(P, cam.eye), 1.0);
            const double iv = focal / (std::max(cellPx, 0.5) * d);
            // S_f: NDC distance outside the frustum, fading over a safety zone.
            const glm::dvec4 c = viewProj * glm::dvec4(P, 1.0);
            double sf = 0.05;
            if (c.w > 0.0) {
                const double outside = std::max(std::fabs(c.x / c.w), std::fabs(c.y / c.w));
                sf = 1.0 - 0.95 * std::clamp((outside - 1.1) / 0.9, 0.0, 1.0);
            }
            // S_b: back-facing slopes (normal away from the eye) need fewer samples.
            const double facing = glm::dot(sketch.normalAt(p), glm::normalize(cam.eye - P));
            const double sb = 1.0 - 0.7 * std::clamp(-facing / 0.3, 0.0, 1.0);
            // I_s: the finest octave that still shows (half a pixel) sets the useful density.
            const double amp = sketch.amplitudeAt(p) * w1 * focal / d;
            int k = 0;
            while (k < kDetailOctaves && std::ldexp(amp, -k) >= 0.5) ++k;
            const double is = std::ldexp(1.0, k) / d0;
            const float v = float(std::min(iv * sf * sb, is));
            m.values[std::size_t(j) * std::size_t(m.size) + std::size_t(i)] = v;
            visible[std::size_t(j) * std::size_t(m.size) + std::size_t(i)] = float(sf);
            peak = std::max(peak, v);
        }
    // A floor of 10 % of the peak and a light smoothing keep the separable warp from folding
    // the grid where the importance changes sharply (frustum edges, the camera's nadir).
    // Visible ground gets at least kVisibleFloor of the peak: the far part of the view must
    // still be sampled at the data's post spacing (the region shrinks until it is).
    for (std::size_t k = 0; k < m.values.size(); ++k)
        m.values[k] =
            std::max({m.values[k], 0.1f * peak + 1e-9f, kVisibleFloor * visible[k] * peak});
    smoothImportance(m, 8);
    return m;
}

}  // namespace kiosk::terrain
