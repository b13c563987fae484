#include "runtime/terrain/GeometryImageWarp.h"

#include <algorithm>
#include <cmath>

namespace kiosk::terrain {

double ImportanceMap::at(const glm::dvec2& p) const {
    if (size < 2 || values.size() < std::size_t(size) * std::size_t(size)) return 1.0;
    const glm::dvec2 ext = glm::max(max - min, glm::dvec2(1e-9));
    const glm::dvec2 u = glm::clamp((p - min) / ext, 0.0, 1.0) * double(size - 1);
    const int x0 = std::min(int(u.x), size - 2), y0 = std::min(int(u.y), size - 2);
    const double ax = u.x - x0, ay = u.y - y0;
    const auto v = [&](int x, int y) {
        return double(values[std::size_t(y) * std::size_t(size) + std::size_t(x)]);
    };
    return (1 - ay) * ((1 - ax) * v(x0, y0) + ax * v(x0 + 1, y0)) +
           ay * ((1 - ax) * v(x0, y0 + 1) + ax * v(x0 + 1, y0 + 1));
}

WarpGrid uniformWarpGrid(const glm::dvec2& min, const glm::dvec2& max, int n) {
    WarpGrid g;
    g.n = std::max(n, 2);
    g.points.resize(std::size_t(g.n) * std::size_t(g.n));
    for (int t = 0; t < g.n; ++t)
        for (int s = 0; s < g.n; ++s)
            g.at(s, t) = min + (max - min) * glm::dvec2(double(s), double(t)) / double(g.n - 1);
    return g;
}

namespace {

/**
 * Redistribute the points of one polyline (DS04 Fig. 5 for one row): the cumulative importance
 * mass along the line is split into n - 1 equal parts. `line` holds the points in order and
 * receives the moved ones; `mass` is scratch.
 */
void warpLine(std::vector<glm::dvec2>& line, std::vector<double>& mass,
              std::vector<glm::dvec2>& out, const ImportanceMap& importance, int substeps) {
    const std::size_t n = line.size();
    mass.assign(n, 0.0);
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const glm::dvec2 a = line[k], b = line[k + 1];
        const double len = glm::distance(a, b);
        double sum = 0.0;
        // Midpoint rule over `substeps` pieces of the segment.
        for (int q = 0; q < substeps; ++q)
            sum += importance.at(glm::mix(a, b, (q + 0.5) / substeps));
        mass[k + 1] = mass[k] + len * sum / substeps;
    }
    const double total = mass[n - 1];
    out.assign(line.begin(), line.end());
    if (!(total > 0.0)) return;
    std::size_t seg = 0;
    for (std::size_t k = 1; k + 1 < n; ++k) {
        const double target = total * double(k) / double(n - 1);
        while (seg + 2 < n && mass[seg + 1] < target) ++seg;
        const double m0 = mass[seg], m1 = mass[seg + 1];
        // Linear in mass within the segment: the importance is taken as constant per piece.
        const double a = m1 > m0 ? std::clamp((target - m0) / (m1 - m0), 0.0, 1.0) : 0.0;
        out[k] = glm::mix(line[seg], line[seg + 1], a);
    }
    line.swap(out);
}

}  // namespace

void warpPass(WarpGrid& g, const ImportanceMap& importance, int substeps) {
    const int n = g.n;
    substeps = std::max(substeps, 1);
    std::vector<glm::dvec2> line(static_cast<std::size_t>(n)), out;
    std::vector<double> mass;
    for (int t = 0; t < n; ++t) {
        for (int s = 0; s < n; ++s) line[std::size_t(s)] = g.at(s, t);
        warpLine(line, mass, out, importance, substeps);
        for (int s = 0; s < n; ++s) g.at(s, t) = line[std::size_t(s)];
    }
    for (int s = 0; s < n; ++s) {
        for (int t = 0; t < n; ++t) line[std::size_t(t)] = g.at(s, t);
        warpLine(line, mass, out, importance, substeps);
        for (int t = 0; t < n; ++t) g.at(s, t) = line[std::size_t(t)];
    }
}

WarpGrid warpGeometryImage(const ImportanceMap& importance, int n, int iterations) {
    WarpGrid g = uniformWarpGrid(importance.min, importance.max, n);
    for (int i = 0; i < iterations; ++i) warpPass(g, importance);
    return g;
}

double sampleSpacing(const WarpGrid& g, int s, int t) {
    const int n = g.n;
    const glm::dvec2 p = g.at(s, t);
    double sum = 0.0;
    int count = 0;
    const int ds[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& d : ds) {
        const int a = s + d[0], b = t + d[1];
        if (a < 0 || b < 0 || a >= n || b >= n) continue;
        sum += glm::distance(p, g.at(a, b));
        ++count;
    }
    return count ? sum / count : 0.0;
}

double maxNeighbourDistance(const WarpGrid& g, int s, int t) {
    const int n = g.n;
    const glm::dvec2 p = g.at(s, t);
    double m = 0.0;
    if (s > 0) m = std::max(m, glm::distance(p, g.at(s - 1, t)));
    if (s + 1 < n) m = std::max(m, glm::distance(p, g.at(s + 1, t)));
    if (t > 0) m = std::max(m, glm::distance(p, g.at(s, t - 1)));
    if (t + 1 < n) m = std::max(m, glm::distance(p, g.at(s, t + 1)));
    return m;
}

void smoothImportance(ImportanceMap& m, int passes) {
    const int n = m.size;
    if (n < 2 || m.values.size() < std::size_t(n) * std::size_t(n)) return;
    std::vector<float> tmp(m.values.size());
    const auto idx = [n](int x, int y) { return std::size_t(y) * std::size_t(n) + std::size_t(x); };
    for (int p = 0; p < passes; ++p) {
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                tmp[idx(x, y)] =
                    0.25f * (m.values[idx(std::max(x - 1, 0), y)] + 2.0f * m.values[idx(x, y)] +
                             m.values[idx(std::min(x + 1, n - 1), y)]);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                m.values[idx(x, y)] =
                    0.25f * (tmp[idx(x, std::max(y - 1, 0))] + 2.0f * tmp[idx(x, y)] +
                             tmp[idx(x, std::min(y + 1, n - 1))]);
    }
}

int cellDiagonal(const WarpGrid& g, int s, int t) {
    const auto cross = [](glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; };
    const glm::dvec2 p00 = g.at(s, t), p10 = g.at(s + 1, t), p11 = g.at(s + 1, t + 1),
                     p01 = g.at(s, t + 1);
    if (cross(p10 - p00, p11 - p00) > 0.0 && cross(p11 - p00, p01 - p00) > 0.0) return 0;
    if (cross(p10 - p00, p01 - p00) > 0.0 && cross(p11 - p10, p01 - p10) > 0.0) return 1;
    return -1;
}

bool warpGridUnfolded(const WarpGrid& g) {
    for (int t = 0; t + 1 < g.n; ++t)
        for (int s = 0; s + 1 < g.n; ++s)
            if (cellDiagonal(g, s, t) < 0) return false;
    return true;
}

}  // namespace kiosk::terrain
