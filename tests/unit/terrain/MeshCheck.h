#pragma once

// Brute-force checks of a TileMesh against the posts it was built from, shared by the RTIN
// builder's and the stored meshes' tests.
#include "runtime/io/StoreTypes.h"
#include "runtime/terrain/RtinMesher.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace kiosk::terrain {

struct PostPos {
    double x, y;
};

// Vertex position -> post coordinates (posts sit at pixel centres).
inline PostPos toPost(const TileMesh& m, std::uint32_t v, const MeshParams& p) {
    const float* f = &m.vertices[std::size_t(v) * TileMesh::kFloatsPerVertex];
    return {f[0] / p.pixelX - 0.5, -f[1] / p.pixelY - 0.5};
}

// Max over all posts of |TIN - post|, by brute force over every surface triangle, plus the
// covered area in post units (must be the whole tile when there is no nodata).
inline std::pair<double, double> bruteForceError(const TileMesh& m, const io::RasterTile& t,
                                                 const MeshParams& p) {
    double maxErr = 0.0, area = 0.0;
    for (std::uint32_t i = 0; i < m.surfaceIndexCount; i += 3) {
        PostPos q[3];
        double z[3];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = m.indices[i + std::uint32_t(k)];
            q[k] = toPost(m, v, p);
            z[k] = m.vertices[std::size_t(v) * TileMesh::kFloatsPerVertex + 2];
        }
        const double a2 =
            (q[1].x - q[0].x) * (q[2].y - q[0].y) - (q[1].y - q[0].y) * (q[2].x - q[0].x);
        area += std::abs(a2) / 2;
        const int x0 = int(std::floor(std::min({q[0].x, q[1].x, q[2].x}) + 0.5));
        const int x1 = int(std::floor(std::max({q[0].x, q[1].x, q[2].x}) + 0.5));
        const int y0 = int(std::floor(std::min({q[0].y, q[1].y, q[2].y}) + 0.5));
        const int y1 = int(std::floor(std::max({q[0].y, q[1].y, q[2].y}) + 0.5));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                auto ef = [&](const PostPos& a, const PostPos& b) {
                    return (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
                };
                double w0 = ef(q[1], q[2]), w1 = ef(q[2], q[0]), w2 = ef(q[0], q[1]);
                if (a2 < 0) {
                    w0 = -w0;
                    w1 = -w1;
                    w2 = -w2;
                }
                const double eps = 1e-6 * std::abs(a2);
                if (w0 < -eps || w1 < -eps || w2 < -eps) continue;
                const double interp = (w0 * z[0] + w1 * z[1] + w2 * z[2]) / std::abs(a2);
                maxErr = std::max(maxErr, std::abs(interp - double(t.at(x, y))));
            }
    }
    return {maxErr, area};
}

}  // namespace kiosk::terrain
