#include "tests/support/MeshFixtures.h"

#include <cmath>

namespace kiosk::test {

render::MeshData gridMesh(int n, double spacing,
                          const std::function<double(double, double)>& height) {
    render::MeshData m;
    auto h = [&](int i, int j) { return height(i * spacing, j * spacing); };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const double dzdx = (h(std::min(i + 1, n - 1), j) - h(std::max(i - 1, 0), j)) /
                                (spacing * (std::min(i + 1, n - 1) - std::max(i - 1, 0)));
            const double dzdy = (h(i, std::min(j + 1, n - 1)) - h(i, std::max(j - 1, 0))) /
                                (spacing * (std::min(j + 1, n - 1) - std::max(j - 1, 0)));
            const double len = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
            for (double v : {i * spacing, j * spacing, h(i, j), -dzdx / len, -dzdy / len, 1.0 / len})
                m.vertices.push_back(float(v));
        }
    }
    for (int j = 0; j + 1 < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
            const auto a = std::uint32_t(j * n + i), b = a + 1, c = a + std::uint32_t(n), d = c + 1;
            // Counter-clockwise seen from above (+z).
            for (std::uint32_t v : {a, b, d, a, d, c}) m.indices.push_back(v);
        }
    }
    return m;
}

}  // namespace kiosk::test
