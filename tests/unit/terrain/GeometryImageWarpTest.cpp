// Importance-driven geometry image warping (DS04 §3): the warped sample density follows the
// importance function; the sketch map's amplitude bound; the TIN read back at its posts.
#include "runtime/terrain/DetailSketch.h"
#include "runtime/terrain/GeometryImageWarp.h"
#include "runtime/terrain/MeshPosts.h"
#include "runtime/terrain/RtinMesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace kiosk::terrain {
namespace {

ImportanceMap mapOf(double size, int n, const std::function<double(glm::dvec2)>& f) {
    ImportanceMap m;
    m.min = glm::dvec2(0.0);
    m.max = glm::dvec2(size);
    m.size = n;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            m.values.push_back(
                float(f(m.min + (m.max - m.min) * glm::dvec2(i, j) / double(n - 1))));
    return m;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// Two halves of a square ask for densities 4 : 1. The warped x spacing must be 1 : 4 (within
// 20 %), measured away from the transition.
TEST(GeometryImageWarp, SpacingRatioFollowsAStepInImportance) {
    const double L = 1000.0;
    const ImportanceMap imp = mapOf(L, 129, [&](glm::dvec2 p) {
        return 1.0 + 3.0 * (1.0 - std::clamp((p.x - 0.45 * L) / (0.1 * L), 0.0, 1.0));
    });
    const WarpGrid g = warpGeometryImage(imp, 97, 1);
    std::vector<double> high, low;
    for (int t = 1; t + 1 < g.n; ++t)
        for (int s = 1; s + 1 < g.n; ++s) {
            const double x = g.at(s, t).x, dx = g.at(s + 1, t).x - g.at(s - 1, t).x;
            if (x < 0.4 * L) high.push_back(0.5 * dx);
            if (x > 0.6 * L) low.push_back(0.5 * dx);
        }
    ASSERT_GT(high.size(), 100u);
    ASSERT_GT(low.size(), 100u);
    const double ratio = median(low) / median(high);
    EXPECT_NEAR(ratio, 4.0, 0.2 * 4.0) << "spacing low / high importance";
    EXPECT_TRUE(warpGridUnfolded(g));
    // The regular grid of the same vertex count is the baseline: ratio 1.
    const WarpGrid u = warpGeometryImage(imp, 97, 0);
    EXPECT_NEAR(sampleSpacing(u, 10, 10) / sampleSpacing(u, 80, 10), 1.0, 1e-9);
}

// A synthetic scene as in DS04 Fig. 3: a Gaussian mountain seen from a low camera. Spacing
// times importance must be the same constant in high- and low-importance regions (the ratio
// of spacings is the inverse ratio of importance) within 20 %, and the grid must not fold.
TEST(GeometryImageWarp, DensityMatchesViewImportanceOnASyntheticScene) {
    DetailSketch sk;
    sk.spacing = 30.0;
    sk.width = sk.height = 129;
    sk.min = glm::dvec2(0.0);
    for (int j = 0; j < sk.height; ++j)
        for (int i = 0; i < sk.width; ++i) {
            const glm::dvec2 p = sk.min + glm::dvec2(i, j) * sk.spacing;
            const double r2 = glm::dot(p - glm::dvec2(2400, 2600), p - glm::dvec2(2400, 2600));
            sk.heights.push_back(float(500.0 + 400.0 * std::exp(-r2 / (900.0 * 900.0)) +
                                       8.0 * std::sin(p.x * 0.09) * std::cos(p.y * 0.07)));
        }
    sk.cap.assign(sk.heights.size(), 5.0f);
    computeDetailAmplitude(sk);
    math::Viewpoint vp;
    vp.target = glm::dvec3(2000, 1800, 600);
    vp.headingDeg = 20;
    vp.pitchDeg = -20;
    vp.range = 900;
    const math::Camera cam = math::Camera::fromViewpoint(vp, 1280, 720, 45);
    const ImportanceMap imp = viewImportance(sk, cam, 4.0, 65);
    const WarpGrid g = warpGeometryImage(imp, 129, 3);
    ASSERT_TRUE(warpGridUnfolded(g));
    float peak = 0.0f, lowest = 1e30f;
    for (float v : imp.values) peak = std::max(peak, v), lowest = std::min(lowest, v);
    ASSERT_GT(peak / lowest, 5.0f) << "the scene must ask for very different densities";
    // Along every grid line (rows, then columns) whose importance varies at least 3x: the
    // spacing at its low-importance samples over the spacing at its high-importance samples,
    // divided by the target I_high / I_low. Measured as spacing * importance (constant when
    // the density matches): 10th over 90th percentile of the line's samples sorted by I.
    const auto lineRatios = [&](const WarpGrid& grid) {
        std::vector<double> ratios;
        for (int dir = 0; dir < 2; ++dir)
            for (int l = 1; l + 1 < grid.n; ++l) {
                std::vector<std::pair<double, double>> v;  // (importance, spacing * importance)
                for (int k = 1; k + 1 < grid.n; ++k) {
                    const glm::dvec2 a = dir ? grid.at(l, k - 1) : grid.at(k - 1, l);
                    const glm::dvec2 b = dir ? grid.at(l, k + 1) : grid.at(k + 1, l);
                    const double i = imp.at(dir ? grid.at(l, k) : grid.at(k, l));
                    v.emplace_back(i, 0.5 * glm::distance(a, b) * i);
                }
                std::sort(v.begin(), v.end());
                if (v.back().first < 3.0 * v.front().first) continue;
                ratios.push_back(v[v.size() / 10].second / v[v.size() * 9 / 10].second);
            }
        return ratios;
    };
    const std::vector<double> warped = lineRatios(g);
    ASSERT_GT(warped.size(), 50u);
    EXPECT_NEAR(median(warped), 1.0, 0.2);
    std::vector<double> sorted = warped;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_GT(sorted[sorted.size() / 10], 0.7) << "90 % of the lines within 30 %";
    // The regular grid of the same vertex count misses the target by far more.
    const std::vector<double> regular = lineRatios(warpGeometryImage(imp, 129, 0));
    EXPECT_LT(median(regular), 0.5);
}

TEST(GeometryImageWarp, BorderSamplesStayOnTheBorder) {
    const ImportanceMap imp = mapOf(500.0, 33, [](glm::dvec2 p) { return 1.0 + p.x * p.y * 1e-4; });
    const WarpGrid g = warpGeometryImage(imp, 41, 2);
    for (int k = 0; k < g.n; ++k) {
        EXPECT_DOUBLE_EQ(g.at(k, 0).y, 0.0);
        EXPECT_DOUBLE_EQ(g.at(k, g.n - 1).y, 500.0);
        EXPECT_DOUBLE_EQ(g.at(0, k).x, 0.0);
        EXPECT_DOUBLE_EQ(g.at(g.n - 1, k).x, 500.0);
    }
}

TEST(DetailSketch, AmplitudeNeverExceedsTheCap) {
    DetailSketch sk;
    sk.spacing = 10.0;
    sk.width = sk.height = 20;
    for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 20; ++i) sk.heights.push_back(float(((i * 7 + j * 13) % 11) * 9.0));
    for (int k = 0; k < 400; ++k) sk.cap.push_back(float(k % 5) * 0.5f);
    computeDetailAmplitude(sk);
    int capped = 0;
    for (std::size_t k = 0; k < sk.amplitude.size(); ++k) {
        EXPECT_LE(sk.amplitude[k], sk.cap[k]);
        EXPECT_GE(sk.amplitude[k], 0.0f);
        capped += sk.amplitude[k] == sk.cap[k] && sk.cap[k] > 0;
    }
    EXPECT_GT(capped, 100);  // rough data: the cap, not the roughness, bounds most posts
}

TEST(DetailSketch, RegionSnapsToThePostLatticeAheadOfTheCamera) {
    math::Viewpoint vp;
    vp.target = glm::dvec3(5000, 5000, 100);
    vp.headingDeg = 90;  // looking east
    vp.pitchDeg = -30;
    vp.range = 600;
    const math::Camera cam = math::Camera::fromViewpoint(vp, 640, 360, 45);
    const glm::dvec2 origin(5.0, 15.0);
    const DetailRegion r =
        planDetailRegion(cam, 100.0, 10.0, origin, glm::dvec2(0), glm::dvec2(20000));
    ASSERT_TRUE(r.valid());
    for (double v :
         {r.min.x - origin.x, r.max.x - origin.x, r.min.y - origin.y, r.max.y - origin.y})
        EXPECT_NEAR(std::remainder(v, 10.0), 0.0, 1e-6);
    EXPECT_GT(0.5 * (r.min.x + r.max.x), cam.eye.x);  // centred ahead (east) of the nadir
    EXPECT_LE(r.max.x - r.min.x, 2 * 128 * 10.0 + 10.0);
    // Outside the data: no region.
    EXPECT_FALSE(
        planDetailRegion(cam, 100.0, 10.0, origin, glm::dvec2(-900), glm::dvec2(-800)).valid());
}

TEST(MeshPosts, TheTinIsReadBackAtItsPosts) {
    io::RasterTile tile;
    tile.postsX = tile.postsY = 17;
    for (int j = 0; j < 17; ++j)
        for (int i = 0; i < 17; ++i)
            tile.values.push_back(float(100.0 + 2.0 * i - 3.0 * j + ((i * j) % 3)));
    MeshParams p;
    p.originX = 1000;
    p.originY = 2000;
    p.pixelX = p.pixelY = 10;
    p.tolerance = 0.0;
    RtinMesher mesher;
    auto mesh = mesher.build(tile, p);
    ASSERT_TRUE(mesh.ok()) << mesh.diagnostics.format();
    const MeshPosts posts = meshPosts(*mesh);
    ASSERT_EQ(posts.size, 17);
    for (int j = 0; j < 17; ++j)
        for (int i = 0; i < 17; ++i)
            EXPECT_NEAR(posts.at(glm::dvec2(1000 + (i + 0.5) * 10, 2000 - (j + 0.5) * 10)),
                        tile.values[std::size_t(j) * 17 + std::size_t(i)], 1e-3);
    EXPECT_TRUE(std::isnan(posts.at(glm::dvec2(900, 2000))));
    // Anywhere inside, the TIN's own triangle: within its cell's post range, exact at posts.
    for (int k = 0; k < 200; ++k) {
        const double fx = 0.5 + 15.9 * ((k * 37) % 101) / 101.0,
                     fy = 0.5 + 15.9 * ((k * 53) % 97) / 97.0;
        double z = 0;
        glm::dvec3 n(0.0);
        ASSERT_TRUE(posts.sample(glm::dvec2(1000 + fx * 10, 2000 - fy * 10), z, n));
        const int i = int(fx - 0.5), j = int(fy - 0.5);
        const auto v = [&](int x, int y) {
            return double(tile.values[std::size_t(y) * 17 + std::size_t(x)]);
        };
        EXPECT_GE(z, std::min({v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)}) - 1e-3);
        EXPECT_LE(z, std::max({v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)}) + 1e-3);
        EXPECT_GT(n.z, 0.0);
    }
    double z = 0;
    glm::dvec3 n(0.0);
    ASSERT_TRUE(posts.sample(glm::dvec2(1000 + 5.5 * 10, 2000 - 7.5 * 10), z, n));
    EXPECT_NEAR(z, tile.values[7 * 17 + 5], 1e-3);
    EXPECT_FALSE(posts.sample(glm::dvec2(900, 2000), z, n));
}

}  // namespace
}  // namespace kiosk::terrain
