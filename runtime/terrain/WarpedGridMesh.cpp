#include "runtime/terrain/WarpedGridMesh.h"

#include <algorithm>
#include <cmath>

namespace kiosk::terrain {

void buildWarpedGridMesh(const WarpGrid& g, const DetailSketch& sk, double fadeWidth,
                         double skirtDepth, WarpedGridMesh& out, const SurfaceSampler& surface) {
    const int n = g.n;
    out.origin = sk.min;
    out.vertices.clear();
    out.indices.clear();
    out.rowStart.clear();
    out.rowY.clear();
    const glm::dvec2 lo = sk.min, hi = sk.max();
    const auto push = [&](const glm::dvec2& p, double skirt, double fade) {
        double z = 0.0;
        glm::dvec3 nrm(0.0, 0.0, 1.0);
        if (!surface || !surface(p, z, nrm)) {
            z = sk.heightAt(p);
            nrm = sk.normalAt(p);
        }
        out.vertices.insert(out.vertices.end(),
                            {float(p.x - out.origin.x), float(p.y - out.origin.y), float(z),
                             float(nrm.x), float(nrm.y), float(nrm.z), float(sk.amplitudeAt(p)),
                             0.0f, float(fade), float(skirt)});
    };
    for (int t = 0; t < n; ++t)
        for (int s = 0; s < n; ++s) {
            const glm::dvec2 p = g.at(s, t);
            const double edge = std::min({p.x - lo.x, hi.x - p.x, p.y - lo.y, hi.y - p.y});
            const double a = std::clamp(edge / std::max(fadeWidth, 1e-9), 0.0, 1.0);
            push(p, 0.0, a * a * (3.0 - 2.0 * a));
            const double d = std::max(maxNeighbourDistance(g, s, t), 1e-9);
            out.vertices[out.vertices.size() - 3] = float(std::log2(sk.spacing / d) - 0.5);
        }
    const auto v = [n](int s, int t) { return std::uint32_t(t * n + s); };
    for (int t = 0; t + 1 < n; ++t) {
        out.rowStart.push_back(std::uint32_t(out.indices.size()));
        double y0 = 1e300, y1 = -1e300;
        for (int s = 0; s < n; ++s)
            for (int k = 0; k < 2; ++k) {
                y0 = std::min(y0, g.at(s, t + k).y);
                y1 = std::max(y1, g.at(s, t + k).y);
            }
        out.rowY.emplace_back(y0, y1);
        for (int s = 0; s + 1 < n; ++s) {
            if (cellDiagonal(g, s, t) == 1)
                out.indices.insert(out.indices.end(), {v(s, t), v(s + 1, t), v(s, t + 1),
                                                       v(s + 1, t), v(s + 1, t + 1), v(s, t + 1)});
            else  // 0, or a folded cell (never seen with the smoothed importance): draw it anyway
                out.indices.insert(out.indices.end(), {v(s, t), v(s + 1, t), v(s + 1, t + 1),
                                                       v(s, t), v(s + 1, t + 1), v(s, t + 1)});
        }
    }
    out.cellTriangles = std::uint32_t(out.indices.size() / 3);
    out.rowStart.push_back(std::uint32_t(out.indices.size()));
    // Skirts: the border walked counter-clockwise, each surface vertex with a copy hanging below.
    std::vector<std::uint32_t> ring;
    for (int s = 0; s + 1 < n; ++s) ring.push_back(v(s, 0));
    for (int t = 0; t + 1 < n; ++t) ring.push_back(v(n - 1, t));
    for (int s = n - 1; s > 0; --s) ring.push_back(v(s, n - 1));
    for (int t = n - 1; t > 0; --t) ring.push_back(v(0, t));
    const std::uint32_t first =
        std::uint32_t(out.vertices.size() / WarpedGridMesh::kFloatsPerVertex);
    for (std::uint32_t top : ring) {
        const std::size_t o = std::size_t(top) * WarpedGridMesh::kFloatsPerVertex;
        for (int k = 0; k < WarpedGridMesh::kFloatsPerVertex; ++k)
            out.vertices.push_back(out.vertices[o + std::size_t(k)]);
        out.vertices.back() = float(skirtDepth);
    }
    const std::uint32_t m = std::uint32_t(ring.size());
    for (std::uint32_t k = 0; k < m; ++k) {
        const std::uint32_t a = ring[k], b = ring[(k + 1) % m], a2 = first + k,
                            b2 = first + (k + 1) % m;
        out.indices.insert(out.indices.end(), {a, a2, b2, a, b2, b});
    }
}

void warpedGridRows(const WarpedGridMesh& mesh, double minY, double maxY, int& first, int& last) {
    first = int(mesh.rowY.size());
    last = 0;
    for (int r = 0; r < int(mesh.rowY.size()); ++r)
        if (mesh.rowY[std::size_t(r)].y >= minY && mesh.rowY[std::size_t(r)].x <= maxY) {
            first = std::min(first, r);
            last = r + 1;
        }
    if (last <= first) first = last = 0;
}

}  // namespace kiosk::terrain
