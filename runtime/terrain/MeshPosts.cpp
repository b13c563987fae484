#include "runtime/terrain/MeshPosts.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kiosk::terrain {

double MeshPosts::at(const glm::dvec2& p) const {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (size < 2) return nan;
    const double fx = (p.x - firstPost.x) / spacing.x, fy = (firstPost.y - p.y) / spacing.y;
    const double eps = 1e-6;
    if (fx < -eps || fy < -eps || fx > size - 1 + eps || fy > size - 1 + eps) return nan;
    const double cx = std::clamp(fx, 0.0, double(size - 1)),
                 cy = std::clamp(fy, 0.0, double(size - 1));
    const int x0 = std::min(int(cx), size - 2), y0 = std::min(int(cy), size - 2);
    const double ax = cx - x0, ay = cy - y0;
    const auto h = [&](int x, int y) {
        return double(z[std::size_t(y) * std::size_t(size) + std::size_t(x)]);
    };
    return (1 - ay) * ((1 - ax) * h(x0, y0) + ax * h(x0 + 1, y0)) +
           ay * ((1 - ax) * h(x0, y0 + 1) + ax * h(x0 + 1, y0 + 1));
}

bool MeshPosts::nearest(const glm::dvec2& p, int& i, int& j) const {
    if (size < 1) return false;
    const double fx = (p.x - firstPost.x) / spacing.x, fy = (firstPost.y - p.y) / spacing.y;
    if (fx < -0.5 || fy < -0.5 || fx > size - 0.5 || fy > size - 0.5) return false;
    i = std::clamp(int(std::lround(fx)), 0, size - 1);
    j = std::clamp(int(std::lround(fy)), 0, size - 1);
    return true;
}

MeshPosts meshPosts(const TileMesh& mesh) {
    MeshPosts out;
    out.size = mesh.postIntervals + 1;
    out.spacing = mesh.postSpacing;
    if (out.size < 2 || !(out.spacing.x > 0.0) || !(out.spacing.y > 0.0)) return {};
    // Posts sit at pixel centres: post (i, j) at origin + ((i + 0.5) px, -(j + 0.5) py).
    out.firstPost = glm::dvec2(mesh.origin) + glm::dvec2(0.5 * out.spacing.x, -0.5 * out.spacing.y);
    out.z.assign(std::size_t(out.size) * std::size_t(out.size),
                 std::numeric_limits<float>::quiet_NaN());
    out.n.assign(out.z.size(), glm::vec3(0.0f, 0.0f, 1.0f));
    const float* v = mesh.vertices.data();
    const auto normalOf = [&](std::uint32_t i) {
        const float* q = v + std::size_t(i) * TileMesh::kFloatsPerVertex + 3;
        return glm::dvec3(q[0], q[1], q[2]);
    };
    const auto postOf = [&](std::uint32_t i) {
        const float* q = v + std::size_t(i) * TileMesh::kFloatsPerVertex;
        return glm::dvec3(q[0] / out.spacing.x - 0.5, -q[1] / out.spacing.y - 0.5, q[2]);
    };
    for (std::uint32_t t = 0; t + 2 < mesh.surfaceIndexCount; t += 3) {
        const std::uint32_t ia = mesh.indices[t], ib = mesh.indices[t + 1], ic = mesh.indices[t + 2];
        const glm::dvec3 a = postOf(ia), b = postOf(ib), c = postOf(ic);
        const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if (std::fabs(area) < 1e-12) continue;
        const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}) + 1e-6)));
        const int x1 = std::min(out.size - 1, int(std::ceil(std::max({a.x, b.x, c.x}) - 1e-6)));
        const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}) + 1e-6)));
        const int y1 = std::min(out.size - 1, int(std::ceil(std::max({a.y, b.y, c.y}) - 1e-6)));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                // Barycentric coordinates; posts on an edge belong to both triangles (same z).
                const double wa = ((b.x - x) * (c.y - y) - (c.x - x) * (b.y - y)) / area;
                const double wb = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area;
                const double wc = 1.0 - wa - wb;
                if (wa < -1e-6 || wb < -1e-6 || wc < -1e-6) continue;
                const std::size_t k = std::size_t(y) * std::size_t(out.size) + std::size_t(x);
                out.z[k] = float(wa * a.z + wb * b.z + wc * c.z);
                out.n[k] = glm::vec3(wa * normalOf(ia) + wb * normalOf(ib) + wc * normalOf(ic));
            }
    }
    return out;
}

}  // namespace kiosk::terrain
