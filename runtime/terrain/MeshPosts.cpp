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

bool MeshPosts::sample(const glm::dvec2& p, double& height, glm::dvec3& normal) const {
    const int cells = size - 1;
    if (cells < 1 || cellStart.size() != std::size_t(cells) * std::size_t(cells) + 1) return false;
    const double fx = (p.x - firstPost.x) / spacing.x, fy = (firstPost.y - p.y) / spacing.y;
    if (fx < -1e-6 || fy < -1e-6 || fx > cells + 1e-6 || fy > cells + 1e-6) return false;
    const int cx = std::clamp(int(fx), 0, cells - 1), cy = std::clamp(int(fy), 0, cells - 1);
    const std::size_t c = std::size_t(cy) * std::size_t(cells) + std::size_t(cx);
    double bestOutside = -1e30;
    for (std::uint32_t k = cellStart[c]; k < cellStart[c + 1]; ++k) {
        const std::uint32_t t = cellTriangles[k];
        const glm::dvec3 a(vertices[indices[t]]), b(vertices[indices[t + 1]]),
            d(vertices[indices[t + 2]]);
        const double area = (b.x - a.x) * (d.y - a.y) - (d.x - a.x) * (b.y - a.y);
        if (std::fabs(area) < 1e-12) continue;
        const double wa = ((b.x - fx) * (d.y - fy) - (d.x - fx) * (b.y - fy)) / area;
        const double wb = ((d.x - fx) * (a.y - fy) - (a.x - fx) * (d.y - fy)) / area;
        const double wc = 1.0 - wa - wb;
        const double inside = std::min({wa, wb, wc});
        // The containing triangle, or on a shared edge the one it is least outside of.
        if (inside < bestOutside) continue;
        bestOutside = inside;
        height = wa * a.z + wb * b.z + wc * d.z;
        normal = glm::dvec3(normals[indices[t]]) * wa + glm::dvec3(normals[indices[t + 1]]) * wb +
                 glm::dvec3(normals[indices[t + 2]]) * wc;
        if (inside >= -1e-9) break;
    }
    return bestOutside > -1e-3;
}

MeshPosts meshPosts(const TileMesh& mesh) {
    MeshPosts out;
    out.size = mesh.postIntervals + 1;
    out.spacing = mesh.postSpacing;
    if (out.size < 2 || !(out.spacing.x > 0.0) || !(out.spacing.y > 0.0) ||
        mesh.indices.size() < mesh.surfaceIndexCount || mesh.vertices.empty())
        return {};
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
        const std::uint32_t ia = mesh.indices[t], ib = mesh.indices[t + 1],
                            ic = mesh.indices[t + 2];
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
    // Cell index for sample(): every triangle listed in each post cell its bounding box meets.
    const int cells = out.size - 1;
    out.vertices.resize(mesh.vertexCount());
    out.normals.resize(mesh.vertexCount());
    for (std::size_t k = 0; k < mesh.vertexCount(); ++k) {
        const glm::dvec3 q = postOf(std::uint32_t(k));
        out.vertices[k] = glm::vec3(q);
        out.normals[k] = glm::vec3(normalOf(std::uint32_t(k)));
    }
    out.indices.assign(mesh.indices.begin(), mesh.indices.begin() + mesh.surfaceIndexCount);
    out.cellStart.assign(std::size_t(cells) * std::size_t(cells) + 1, 0);
    const auto forCells = [&](std::uint32_t t, auto&& fn) {
        const glm::vec3 a = out.vertices[out.indices[t]], b = out.vertices[out.indices[t + 1]],
                        c = out.vertices[out.indices[t + 2]];
        const int x0 = std::clamp(int(std::floor(std::min({a.x, b.x, c.x}) - 1e-4f)), 0, cells - 1);
        const int x1 =
            std::clamp(int(std::ceil(std::max({a.x, b.x, c.x}) + 1e-4f)) - 1, 0, cells - 1);
        const int y0 = std::clamp(int(std::floor(std::min({a.y, b.y, c.y}) - 1e-4f)), 0, cells - 1);
        const int y1 =
            std::clamp(int(std::ceil(std::max({a.y, b.y, c.y}) + 1e-4f)) - 1, 0, cells - 1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) fn(std::size_t(y) * std::size_t(cells) + std::size_t(x));
    };
    for (std::uint32_t t = 0; t + 2 < mesh.surfaceIndexCount; t += 3)
        forCells(t, [&](std::size_t c) { ++out.cellStart[c + 1]; });
    for (std::size_t c = 1; c < out.cellStart.size(); ++c) out.cellStart[c] += out.cellStart[c - 1];
    out.cellTriangles.resize(out.cellStart.back());
    std::vector<std::uint32_t> fill(out.cellStart.begin(), out.cellStart.end() - 1);
    for (std::uint32_t t = 0; t + 2 < mesh.surfaceIndexCount; t += 3)
        forCells(t, [&](std::size_t c) { out.cellTriangles[fill[c]++] = t; });
    return out;
}

}  // namespace kiosk::terrain
