#include "runtime/mapping/RouteMappings.h"

#include <algorithm>
#include <cmath>

namespace kiosk::mapping {
namespace {

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

std::uint8_t dn(double a) {
    return std::uint8_t(std::lround(std::clamp(a, 0.0, 1.0) * 255.0));
}

}  // namespace

std::vector<RoutePiece> routeMappings(const MappingState& base,
                                      const std::vector<glm::dvec2>& points, double width,
                                      double pointRadius) {
    std::vector<RoutePiece> out;
    const double z = base.origin.z;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        const glm::dvec2 d = points[i + 1] - points[i];
        const double len = glm::length(d);
        if (!(len > 0.0) || !(width > 0.0)) continue;
        const glm::dvec2 dir = d / len;
        RoutePiece p{RoutePieceKind::Edge, base};
        p.state.origin = glm::dvec3((points[i] + points[i + 1]) * 0.5, z);
        p.state.u = glm::dvec3(dir * (len + width), 0.0);
        // N × Û with N = +z: the left-hand normal of the segment.
        p.state.v = glm::dvec3(-dir.y * width, dir.x * width, 0.0);
        p.state.textureMatrix = glm::dmat3(1.0);
        out.push_back(p);
    }
    if (pointRadius > 0.0) {
        for (const auto& w : points) {
            RoutePiece p{RoutePieceKind::Point, base};
            p.state.origin = glm::dvec3(w, z);
            p.state.u = glm::dvec3(2.0 * pointRadius, 0.0, 0.0);
            p.state.v = glm::dvec3(0.0, 2.0 * pointRadius, 0.0);
            p.state.textureMatrix = glm::dmat3(1.0);
            out.push_back(p);
        }
    }
    return out;
}

std::vector<std::uint8_t> edgeProfileImage(int size) {
    const int n = std::max(size, 2);
    std::vector<std::uint8_t> img(std::size_t(n) * std::size_t(n) * 4, 255);
    for (int y = 0; y < n; ++y) {
        const double t = double(y) / (n - 1);         // the border rows reach alpha 0 exactly
        const double dist = std::abs(t - 0.5) * 2.0;  // 0 centre .. 1 edge
        const std::uint8_t a = dn(1.0 - smoothstep(0.6, 1.0, dist));
        for (int x = 0; x < n; ++x)
            img[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 4 + 3] = a;
    }
    return img;
}

std::vector<std::uint8_t> discImage(int size) {
    const int n = std::max(size, 2);
    std::vector<std::uint8_t> img(std::size_t(n) * std::size_t(n) * 4, 255);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double r = std::hypot(double(x) / (n - 1) - 0.5, double(y) / (n - 1) - 0.5);
            img[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 4 + 3] =
                dn(1.0 - smoothstep(0.4, 0.5, r));
        }
    return img;
}

}  // namespace kiosk::mapping
