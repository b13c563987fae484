// Synthetic surfaces whose shading, shadows and normals are known analytically, plus the
// nodata, tiling and bad-input contracts of kiosk_topo.

#include "runtime/topo/Hillshade.h"
#include "runtime/topo/NormalMap.h"
#include "runtime/topo/Shadow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace kiosk::topo {
namespace {

constexpr double kPi = std::numbers::pi;

struct Grid {
    int width = 0;
    int height = 0;
    std::vector<float> h;
    float& at(int c, int r) { return h[static_cast<std::size_t>(r) * width + c]; }
    RasterView view(double pixel) const {
        return RasterView::window(h.data(), width, height, width, 0, 0, width, height, pixel,
                                  pixel);
    }
};

// Cone of height `top` and slope `slope` (rise per metre) centred on the grid.
Grid cone(int n, double pixel, double top, double slope) {
    Grid g{n, n, std::vector<float>(static_cast<std::size_t>(n) * n)};
    const double cx = (n - 1) / 2.0;
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
            const double d = std::hypot(c - cx, r - cx) * pixel;
            g.at(c, r) = static_cast<float>(top - slope * d);
        }
    return g;
}

// Analytic unit normal of the cone at (c, r): it falls away radially. East = +c, north = -r.
std::array<double, 3> coneNormal(int n, int c, int r, double slope) {
    const double cx = (n - 1) / 2.0;
    const double e = c - cx;
    const double nn = -(r - cx);
    const double len = std::hypot(e, nn);
    // z = top - slope * dist -> gradient = -slope * radial unit; normal = (-grad, 1).
    const double gx = -slope * e / len;
    const double gy = -slope * nn / len;
    const double inv = 1.0 / std::sqrt(gx * gx + gy * gy + 1.0);
    return {-gx * inv, -gy * inv, inv};
}

std::array<double, 3> lightVector(double azDeg, double altDeg) {
    const double az = azDeg * kPi / 180.0;
    const double alt = altDeg * kPi / 180.0;
    return {std::sin(az) * std::cos(alt), std::cos(az) * std::cos(alt), std::sin(alt)};
}

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

TEST(HillshadeSyntheticTest, ConeMatchesLambertOfAnalyticNormal) {
    const int n = 129;
    const double slope = 0.6;
    const Grid g = cone(n, 10.0, 1000.0, slope);
    for (const double az : {315.0, 90.0, 200.0}) {
        HillshadeParams p;
        p.azimuthDeg = az;
        p.altitudeDeg = 40.0;
        std::vector<std::uint8_t> out(g.h.size());
        ASSERT_FALSE(hillshade(g.view(10.0), p, out.data(), n).hasErrors());
        const auto light = lightVector(az, 40.0);
        int checked = 0;
        int worst = 0;
        for (int r = 1; r < n - 1; ++r)
            for (int c = 1; c < n - 1; ++c) {
                // Away from the apex: Horn's 3x3 window sees a nearly planar cone there.
                if (std::hypot(c - (n - 1) / 2.0, r - (n - 1) / 2.0) < 12.0) continue;
                const double lambert = dot(coneNormal(n, c, r, slope), light);
                const int expected =
                    lambert <= 0 ? 1 : static_cast<int>(1.0 + 254.0 * lambert + 0.5);
                const int diff = std::abs(out[static_cast<std::size_t>(r) * n + c] - expected);
                worst = std::max(worst, diff);
                ++checked;
                ASSERT_LE(diff, 1) << "az " << az << " at (" << c << "," << r << ")";
            }
        EXPECT_GT(checked, n * n / 2);
        // The cone's border ring is nodata without computeEdges (gdaldem's rule).
        EXPECT_EQ(out[0], kHillshadeNodata);
        EXPECT_EQ(out[static_cast<std::size_t>(n) * n - 1], kHillshadeNodata);
    }
}

TEST(HillshadeSyntheticTest, FlatGroundIsSinAltitude) {
    Grid g{16, 16, std::vector<float>(256, 123.0f)};
    HillshadeParams p;
    p.computeEdges = true;
    for (const auto variant : {HillshadeVariant::Default, HillshadeVariant::Multidirectional}) {
        p.variant = variant;
        std::vector<std::uint8_t> out(256);
        ASSERT_FALSE(hillshade(g.view(30.0), p, out.data(), 16).hasErrors());
        const int expected = static_cast<int>(1.0 + 254.0 * std::sin(45.0 * kPi / 180.0) + 0.5);
        for (std::uint8_t v : out) ASSERT_EQ(v, expected);
    }
}

// A hole of nodata in a slope: the hole stays nodata (transparent, 0); its neighbours are
// either nodata too (gdaldem's default) or shaded like the rest of the slope (computeEdges),
// never a black (1) or white (255) rim.
TEST(HillshadeSyntheticTest, NodataStaysTransparentWithoutRim) {
    const int n = 40;
    Grid g{n, n, std::vector<float>(static_cast<std::size_t>(n) * n)};
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) g.at(c, r) = static_cast<float>(3.0 * c + 1.5 * r);
    for (int r = 15; r < 25; ++r)
        for (int c = 12; c < 20; ++c) g.at(c, r) = NAN;
    for (const bool edges : {false, true}) {
        HillshadeParams p;
        p.computeEdges = edges;
        std::vector<std::uint8_t> out(g.h.size());
        ASSERT_FALSE(hillshade(g.view(10.0), p, out.data(), n).hasErrors());
        const int planeValue = out[5 * n + 5];
        ASSERT_GT(planeValue, 1);
        ASSERT_LT(planeValue, 255);
        for (int r = 1; r < n - 1; ++r)
            for (int c = 1; c < n - 1; ++c) {
                const int v = out[static_cast<std::size_t>(r) * n + c];
                const bool hole = r >= 15 && r < 25 && c >= 12 && c < 20;
                const bool ring = r >= 14 && r < 26 && c >= 11 && c < 21;
                if (hole)
                    EXPECT_EQ(v, kHillshadeNodata) << c << "," << r;
                else if (ring && !edges)
                    EXPECT_EQ(v, kHillshadeNodata) << c << "," << r;
                else if (ring)
                    // gdaldem -compute_edges substitutes the centre height for a nodata
                    // neighbour: the gradient across the hole's edge is at most halved, a
                    // faint change of shade, not a black (1) or white (255) outline.
                    EXPECT_NEAR(v, planeValue, 20) << c << "," << r;
                else
                    EXPECT_NEAR(v, planeValue, 1) << "edges " << edges << " at " << c << "," << r;
            }
    }
}

// Tiles cut with RasterView::window() (1-pixel apron) reproduce the whole-DEM hillshade
// exactly, including the DEM border rules at the outer tiles.
TEST(HillshadeSyntheticTest, TilesAreSeamless) {
    const int n = 100;
    Grid g{n, n, std::vector<float>(static_cast<std::size_t>(n) * n)};
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            g.at(c, r) = static_cast<float>(200.0 * std::sin(c * 0.13) * std::cos(r * 0.07) +
                                            (c * 31 + r * 17) % 11);
    g.at(40, 40) = NAN;  // a hole straddling tile corners
    for (const bool edges : {false, true}) {
        HillshadeParams p;
        p.computeEdges = edges;
        std::vector<std::uint8_t> whole(g.h.size());
        ASSERT_FALSE(hillshade(g.view(25.0), p, whole.data(), n).hasErrors());
        std::vector<std::uint8_t> tiled(g.h.size(), 99);
        const int tile = 41;  // not a divisor: ragged last tiles
        for (int y0 = 0; y0 < n; y0 += tile)
            for (int x0 = 0; x0 < n; x0 += tile) {
                const RasterView v =
                    RasterView::window(g.h.data(), n, n, n, x0, y0, tile, tile, 25.0, 25.0, 1);
                ASSERT_FALSE(hillshade(v, p, tiled.data() + y0 * n + x0, n).hasErrors());
            }
        EXPECT_EQ(tiled, whole) << "computeEdges " << edges;
    }
}

// Degenerate DEMs (one row, one column, one pixel, all nodata) go through the border paths
// without reading outside the view; the output is shading or nodata, never garbage.
TEST(HillshadeSyntheticTest, TinyAndEmptyDemsAreHandled) {
    const std::pair<int, int> sizes[] = {{1, 1}, {1, 5}, {5, 1}, {2, 2}, {3, 2}};
    for (const auto& [w, h] : sizes) {
        for (const bool allNodata : {false, true}) {
            std::vector<float> dem(static_cast<std::size_t>(w) * h);
            for (std::size_t i = 0; i < dem.size(); ++i)
                dem[i] = allNodata ? NAN : static_cast<float>(i * 7 % 5);
            const RasterView v = RasterView::window(dem.data(), w, h, w, 0, 0, w, h, 10, 10);
            for (const bool edges : {false, true}) {
                HillshadeParams p;
                p.computeEdges = edges;
                std::vector<std::uint8_t> out(dem.size(), 77), mask(dem.size(), 77);
                std::vector<std::uint8_t> normals(dem.size() * 3, 77);
                ASSERT_FALSE(hillshade(v, p, out.data(), w).hasErrors());
                ASSERT_FALSE(castShadows(v, p, mask.data(), w).hasErrors());
                NormalMapParams np;
                np.computeEdges = edges;
                ASSERT_FALSE(normalMap(v, np, normals.data(), w * 3).hasErrors());
                for (std::size_t i = 0; i < dem.size(); ++i) {
                    EXPECT_TRUE(mask[i] == kLit || mask[i] == kShadowed);
                    if (allNodata || !edges) {
                        EXPECT_EQ(out[i], kHillshadeNodata);
                    } else {
                        EXPECT_GE(out[i], 1);
                        EXPECT_GE(normals[i * 3 + 2], 128);
                    }
                    if (allNodata) {
                        EXPECT_EQ(normals[i * 3 + 2], 0);
                    }
                }
            }
        }
    }
}

// Ridge: a wall `height` high along a column on flat ground, sun from the west (or north).
// The shadow behind it is height / tan(altitude) long.
TEST(ShadowTest, RidgeShadowLengthMatchesGeometry) {
    const int n = 200;
    const double pixel = 10.0;
    for (const double alt : {20.0, 35.0, 60.0}) {
        for (const double height : {100.0, 237.0}) {
            Grid g{n, n, std::vector<float>(static_cast<std::size_t>(n) * n, 0.0f)};
            const int wall = 30;
            for (int r = 0; r < n; ++r) g.at(wall, r) = static_cast<float>(height);
            HillshadeParams p;
            p.azimuthDeg = 270.0;  // light from the west: the shadow falls east
            p.altitudeDeg = alt;
            std::vector<std::uint8_t> mask(g.h.size());
            ASSERT_FALSE(castShadows(g.view(pixel), p, mask.data(), n).hasErrors());
            const double expected = height / std::tan(alt * kPi / 180.0) / pixel;
            for (int r = 0; r < n; ++r) {
                int len = 0;
                while (wall + 1 + len < n && mask[r * n + wall + 1 + len] == kShadowed) ++len;
                ASSERT_NEAR(len, expected, 1.0) << "alt " << alt << " height " << height;
                // Nothing west of the wall is shadowed, and the shadow ends.
                for (int c = 0; c <= wall; ++c) ASSERT_EQ(mask[r * n + c], kLit);
                ASSERT_EQ(mask[r * n + wall + 1 + len], kLit);
            }
        }
    }
}

// The same with a diagonal sun (azimuth 315) over a wall running south-west to north-east:
// the shadow, measured along the light direction, is still height / tan(altitude).
TEST(ShadowTest, DiagonalRidgeShadowLength) {
    const int n = 240;
    const double pixel = 5.0;
    const double height = 150.0;
    const double alt = 30.0;
    Grid g{n, n, std::vector<float>(static_cast<std::size_t>(n) * n, 0.0f)};
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            if (c + r == 120) g.at(c, r) = static_cast<float>(height);
    HillshadeParams p;
    p.azimuthDeg = 315.0;
    p.altitudeDeg = alt;
    std::vector<std::uint8_t> mask(g.h.size());
    ASSERT_FALSE(castShadows(g.view(pixel), p, mask.data(), n).hasErrors());
    // Along the diagonal from a wall pixel towards south-east, one step = pixel * sqrt(2).
    const double expectedSteps = height / std::tan(alt * kPi / 180.0) / (pixel * std::sqrt(2.0));
    for (int c0 = 40; c0 <= 80; c0 += 10) {
        const int r0 = 120 - c0;
        int len = 0;
        while (mask[(r0 + 1 + len) * n + c0 + 1 + len] == kShadowed) ++len;
        EXPECT_NEAR(len, expectedSteps, 1.0) << "from (" << c0 << "," << r0 << ")";
    }
}

TEST(ShadowTest, ShadowsAreSeamlessAcrossTilesWithRequiredApron) {
    const int n = 160;
    const double pixel = 20.0;
    Grid g{n, n, std::vector<float>(static_cast<std::size_t>(n) * n)};
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            g.at(c, r) = static_cast<float>(300.0 * std::sin(c * 0.11) * std::sin(r * 0.05) +
                                            150.0 * std::cos(c * 0.031 + r * 0.047));
    HillshadeParams p;
    p.azimuthDeg = 250.0;
    p.altitudeDeg = 25.0;
    std::vector<std::uint8_t> whole(g.h.size());
    ASSERT_FALSE(castShadows(g.view(pixel), p, whole.data(), n).hasErrors());
    long long shadowed = 0;
    for (auto v : whole) shadowed += v == kShadowed;
    ASSERT_GT(shadowed, n * n / 20);  // the scene really has shadows
    ASSERT_LT(shadowed, n * n * 9 / 10);

    float lo = g.h[0], hi = g.h[0];
    for (float v : g.h) lo = std::min(lo, v), hi = std::max(hi, v);
    const int apron = requiredShadowApron(hi - lo, p, pixel, pixel);
    EXPECT_EQ(apron,
              static_cast<int>(std::ceil((hi - lo) / std::tan(25.0 * kPi / 180.0) / pixel)) + 1);
    std::vector<std::uint8_t> tiled(g.h.size(), 7);
    const int tile = 50;
    for (int y0 = 0; y0 < n; y0 += tile)
        for (int x0 = 0; x0 < n; x0 += tile) {
            const RasterView v =
                RasterView::window(g.h.data(), n, n, n, x0, y0, tile, tile, pixel, pixel, apron);
            ASSERT_FALSE(castShadows(v, p, tiled.data() + y0 * n + x0, n).hasErrors());
        }
    EXPECT_EQ(tiled, whole);
}

// Reference: the plain per-pixel march with no acceleration (every step sampled, stop only at
// the view's edge). castShadows() skips cells and uses a Lipschitz bound; both must agree.
std::vector<std::uint8_t> bruteForceShadows(const Grid& g, double pixel, double azDeg,
                                            double altDeg) {
    const double az = azDeg * kPi / 180.0;
    double ux = std::sin(az) / pixel, uy = -std::cos(az) / pixel;
    const double m = std::max(std::abs(ux), std::abs(uy));
    ux /= m;
    uy /= m;
    if (std::abs(ux) < 1e-9) ux = 0;
    if (std::abs(uy) < 1e-9) uy = 0;
    const double rise = std::tan(altDeg * kPi / 180.0) / m;
    std::vector<std::uint8_t> mask(g.h.size(), kLit);
    auto at = [&](int c, int r) { return g.h[static_cast<std::size_t>(r) * g.width + c]; };
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c) {
            const float h0 = at(c, r);
            if (!std::isfinite(h0)) continue;
            for (int i = 1;; ++i) {
                const double x = c + ux * i, y = r + uy * i;
                if (x < 0 || y < 0 || x > g.width - 1 || y > g.height - 1) break;
                const int fx = static_cast<int>(x), fy = static_cast<int>(y);
                const double tx = x - fx, ty = y - fy;  // one of them is 0
                float a = at(fx, fy);
                double h = a;
                if (tx > 0 || ty > 0) {
                    const float b = tx > 0 ? at(fx + 1, fy) : at(fx, fy + 1);
                    const double t = tx > 0 ? tx : ty;
                    h = std::isfinite(a) && std::isfinite(b) ? a + (b - a) * t
                        : std::isfinite(b)                   ? b
                                                             : a;
                }
                if (std::isfinite(h) && h > h0 + i * rise) {
                    mask[static_cast<std::size_t>(r) * g.width + c] = kShadowed;
                    break;
                }
            }
        }
    return mask;
}

TEST(ShadowTest, AcceleratedMarchEqualsBruteForce) {
    const int n = 120;
    const double pixel = 15.0;
    Grid g{n, n, std::vector<float>(static_cast<std::size_t>(n) * n)};
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            g.at(c, r) =
                static_cast<float>(250.0 * std::sin(c * 0.09) * std::cos(r * 0.05) +
                                   90.0 * std::sin(c * 0.3 + r) + ((c * 131 + r * 71) % 17) * 3.0);
    for (int r = 50; r < 58; ++r)
        for (int c = 60; c < 75; ++c) g.at(c, r) = NAN;
    long long shadowedTotal = 0;
    for (const double az : {0.0, 37.0, 90.0, 135.0, 200.0, 270.0, 315.0, 333.0})
        for (const double alt : {8.0, 25.0, 50.0}) {
            HillshadeParams p;
            p.azimuthDeg = az;
            p.altitudeDeg = alt;
            std::vector<std::uint8_t> fast(g.h.size());
            ASSERT_FALSE(castShadows(g.view(pixel), p, fast.data(), n).hasErrors());
            const auto slow = bruteForceShadows(g, pixel, az, alt);
            long long differ = 0;
            for (std::size_t i = 0; i < fast.size(); ++i) differ += fast[i] != slow[i];
            for (auto v : slow) shadowedTotal += v == kShadowed;
            EXPECT_EQ(differ, 0) << "az " << az << " alt " << alt;
        }
    EXPECT_GT(shadowedTotal, 24LL * n * n / 20);  // the terrain casts plenty of shadows
}

TEST(ShadowTest, CombineDarkensOnlyShadowedShading) {
    std::vector<std::uint8_t> shade{0, 1, 101, 255, 201, 255};
    const std::vector<std::uint8_t> mask{255, 255, 255, 255, 0, 128};
    ASSERT_FALSE(
        combineShadows(shade.data(), 6, mask.data(), 6, 6, 1, ShadowParams{0.5}).hasErrors());
    // nodata stays 0; 1 stays 1; 1 + (v - 1) * 0.5 in full shadow; lit untouched; partial.
    const std::vector<std::uint8_t> expected{
        0,   1,   51,
        128, 201, static_cast<std::uint8_t>(1.0 + 254.0 * (1.0 - 0.5 * 128 / 255.0) + 0.5)};
    EXPECT_EQ(shade, expected);
}

TEST(ShadowTest, ShadedReliefDarkensTheShadowBehindTheWall) {
    const int n = 64;
    Grid g{n, n, std::vector<float>(static_cast<std::size_t>(n) * n, 0.0f)};
    for (int r = 0; r < n; ++r) g.at(10, r) = 100.0f;
    HillshadeParams p;
    p.azimuthDeg = 270.0;
    p.altitudeDeg = 45.0;
    p.computeEdges = true;
    std::vector<std::uint8_t> plain(g.h.size()), shaded(g.h.size());
    ASSERT_FALSE(hillshade(g.view(10.0), p, plain.data(), n).hasErrors());
    ASSERT_FALSE(shadedRelief(g.view(10.0), p, ShadowParams{1.0}, shaded.data(), n).hasErrors());
    // 100 m / tan 45 = 10 pixels of shadow east of the wall; flat ground beyond it is lit.
    EXPECT_EQ(shaded[32 * n + 16], 1);
    EXPECT_EQ(shaded[32 * n + 40], plain[32 * n + 40]);
    EXPECT_EQ(plain[32 * n + 40], static_cast<int>(1.0 + 254.0 * std::sqrt(0.5) + 0.5));
}

// Normals of a cone: decode(encode(normal)) vs the analytic normal, and Lambert lighting from
// the decoded normal vs Lambert of the analytic normal, within 2 DN.
TEST(NormalMapTest, ConeNormalsMatchAnalyticWithinTwoDn) {
    const int n = 129;
    const double slope = 0.8;
    const Grid g = cone(n, 10.0, 2000.0, slope);
    for (const auto enc : {NormalEncoding::Rgb8, NormalEncoding::Octahedral8}) {
        NormalMapParams p;
        p.encoding = enc;
        const int bpt = bytesPerTexel(enc);
        std::vector<std::uint8_t> out(g.h.size() * bpt);
        ASSERT_FALSE(normalMap(g.view(10.0), p, out.data(), n * bpt).hasErrors());
        int checked = 0;
        for (int r = 1; r < n - 1; ++r)
            for (int c = 1; c < n - 1; ++c) {
                if (std::hypot(c - (n - 1) / 2.0, r - (n - 1) / 2.0) < 20.0) continue;
                const std::uint8_t* texel = &out[(static_cast<std::size_t>(r) * n + c) * bpt];
                const auto truth = coneNormal(n, c, r, slope);
                std::uint8_t expected[3];
                encodeNormal(truth, enc, expected);
                for (int i = 0; i < bpt; ++i)
                    ASSERT_LE(std::abs(texel[i] - expected[i]), 2)
                        << "channel " << i << " at " << c << "," << r;
                // Lambert as an 8-bit luminance (what a shader writes): DN = round(255 * l).
                const auto dec = decodeNormal(texel, enc);
                for (const double az : {0.0, 135.0, 315.0}) {
                    const auto light = lightVector(az, 35.0);
                    const double ours =
                        std::max(0.0, dec[0] * light[0] + dec[1] * light[1] + dec[2] * light[2]);
                    const double exact = std::max(0.0, dot(truth, light));
                    const long dnOurs = std::lround(ours * 255.0);
                    const long dnExact = std::lround(exact * 255.0);
                    ASSERT_LE(std::abs(dnOurs - dnExact), 2)
                        << "encoding " << static_cast<int>(enc) << " az " << az << " at " << c
                        << "," << r;
                }
                ++checked;
            }
        EXPECT_GT(checked, n * n / 2);
    }
}

TEST(NormalMapTest, NodataTexelsAreZeroAndDecodeToZero) {
    Grid g{8, 8, std::vector<float>(64, 10.0f)};
    g.at(3, 3) = NAN;
    for (const auto enc : {NormalEncoding::Rgb8, NormalEncoding::Octahedral8}) {
        NormalMapParams p;
        p.encoding = enc;
        const int bpt = bytesPerTexel(enc);
        std::vector<std::uint8_t> out(64 * bpt, 9);
        ASSERT_FALSE(normalMap(g.view(1.0), p, out.data(), 8 * bpt).hasErrors());
        const std::uint8_t* hole = &out[(3 * 8 + 3) * bpt];
        for (int i = 0; i < bpt; ++i) EXPECT_EQ(hole[i], 0);
        EXPECT_EQ(decodeNormal(hole, enc), (std::array<float, 3>{0, 0, 0}));
        // A flat neighbour of the hole (computeEdges) points straight up.
        const auto up = decodeNormal(&out[(3 * 8 + 4) * bpt], enc);
        EXPECT_NEAR(up[2], 1.0f, 1e-3f);
    }
}

// Hillshade reproduced from the normal map with the same light: the normal map carries the
// hillshade's gradient.
TEST(NormalMapTest, LambertOfNormalMapReproducesHillshade) {
    const Grid g = cone(65, 30.0, 900.0, 0.4);
    HillshadeParams hp;
    hp.computeEdges = true;
    std::vector<std::uint8_t> shade(g.h.size());
    ASSERT_FALSE(hillshade(g.view(30.0), hp, shade.data(), 65).hasErrors());
    NormalMapParams np;
    std::vector<std::uint8_t> normals(g.h.size() * 3);
    ASSERT_FALSE(normalMap(g.view(30.0), np, normals.data(), 65 * 3).hasErrors());
    const auto light = lightVector(hp.azimuthDeg, hp.altitudeDeg);
    for (std::size_t i = 0; i < g.h.size(); ++i) {
        const auto n = decodeNormal(&normals[i * 3], NormalEncoding::Rgb8);
        const double l = n[0] * light[0] + n[1] * light[1] + n[2] * light[2];
        const double v = l <= 0 ? 1.0 : 1.0 + 254.0 * l;
        ASSERT_NEAR(v, shade[i], 2.5) << "pixel " << i;
    }
}

// Bad input: every function reports a stable code and names the problem; nothing crashes.
struct BadCase {
    const char* name;
    RasterView view;
    HillshadeParams params;
    bool nullOut;
    std::ptrdiff_t outStride;
    const char* code;
    const char* message;
};

const float kSmall[16] = {};

RasterView smallView() {
    return RasterView::window(kSmall, 4, 4, 4, 0, 0, 4, 4, 1.0, 1.0);
}

RasterView with(RasterView v, void (*edit)(RasterView&)) {
    edit(v);
    return v;
}

HillshadeParams withP(void (*edit)(HillshadeParams&)) {
    HillshadeParams p;
    edit(p);
    return p;
}

const BadCase kBad[] = {
    {"NullData",
     with(smallView(), [](RasterView& v) { v.data = nullptr; }),
     {},
     false,
     4,
     "TOPO_INVALID_VIEW",
     "no data"},
    {"Empty",
     with(smallView(), [](RasterView& v) { v.width = 0; }),
     {},
     false,
     4,
     "TOPO_INVALID_VIEW",
     "empty (0 x 4)"},
    {"NegativeApron",
     with(smallView(), [](RasterView& v) { v.apronLeft = -1; }),
     {},
     false,
     4,
     "TOPO_INVALID_VIEW",
     "negative apron"},
    {"ShortStride",
     with(smallView(), [](RasterView& v) { v.stride = 3; }),
     {},
     false,
     4,
     "TOPO_INVALID_VIEW",
     "stride 3"},
    {"ZeroPixel",
     with(smallView(), [](RasterView& v) { v.pixelSizeX = 0; }),
     {},
     false,
     4,
     "TOPO_INVALID_VIEW",
     "pixel size"},
    {"NanPixel",
     with(smallView(), [](RasterView& v) { v.pixelSizeY = NAN; }),
     {},
     false,
     4,
     "TOPO_INVALID_VIEW",
     "pixel size"},
    {"Altitude", smallView(), withP([](HillshadeParams& p) { p.altitudeDeg = 91; }), false, 4,
     "TOPO_INVALID_PARAMS", "altitude"},
    {"Azimuth", smallView(), withP([](HillshadeParams& p) { p.azimuthDeg = INFINITY; }), false, 4,
     "TOPO_INVALID_PARAMS", "azimuth"},
    {"Scale", smallView(), withP([](HillshadeParams& p) { p.scale = 0; }), false, 4,
     "TOPO_INVALID_PARAMS", "scale"},
    {"ZFactor", smallView(), withP([](HillshadeParams& p) { p.zFactor = NAN; }), false, 4,
     "TOPO_INVALID_PARAMS", "zFactor"},
    {"NullOutput", smallView(), {}, true, 4, "TOPO_INVALID_OUTPUT", "null"},
    {"OutputStride", smallView(), {}, false, 2, "TOPO_INVALID_OUTPUT", "stride 2"},
};

class TopoBadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(TopoBadInputTest, ReportsCodeAndMessage) {
    const BadCase& tc = GetParam();
    std::uint8_t out[64];
    std::fill(std::begin(out), std::end(out), std::uint8_t{42});
    std::uint8_t* o = tc.nullOut ? nullptr : out;
    auto check = [&](const Diagnostics& d, const char* fn, bool message = true) {
        ASSERT_TRUE(d.hasErrors()) << fn;
        ASSERT_TRUE(d.has(tc.code)) << fn << ": " << d.format();
        if (message) {
            EXPECT_NE(d.format().find(tc.message), std::string::npos) << fn << ": " << d.format();
        }
        EXPECT_NE(d.format().find(fn), std::string::npos) << d.format();
    };
    check(hillshade(tc.view, tc.params, o, tc.outStride), "hillshade");
    check(castShadows(tc.view, tc.params, o, tc.outStride), "castShadows");
    NormalMapParams np;
    np.zFactor = tc.params.zFactor;
    np.scale = tc.params.scale;
    np.encoding = NormalEncoding::Octahedral8;
    // Octahedral texels are 2 bytes: the stride limit doubles.
    if (std::string(tc.code) != "TOPO_INVALID_PARAMS" || std::string(tc.message) == "scale" ||
        std::string(tc.message) == "zFactor")
        check(normalMap(tc.view, np, o, tc.outStride * 2), "normalMap",
              std::string(tc.name) != "OutputStride");
    for (std::uint8_t v : out) ASSERT_EQ(v, 42) << "nothing may be written on error";
}

INSTANTIATE_TEST_SUITE_P(Table, TopoBadInputTest, ::testing::ValuesIn(kBad),
                         [](const auto& p) { return std::string(p.param.name); });

TEST(TopoBadInputTest, ShadowDarkeningOutOfRange) {
    std::uint8_t shade[4] = {10, 10, 10, 10};
    const std::uint8_t mask[4] = {255, 255, 255, 255};
    const Diagnostics d = combineShadows(shade, 4, mask, 4, 4, 1, ShadowParams{1.5});
    EXPECT_TRUE(d.has("TOPO_INVALID_PARAMS"));
    EXPECT_NE(d.format().find("darkening"), std::string::npos);
    EXPECT_EQ(shade[0], 10);
}

TEST(RasterViewTest, WindowClipsAndSetsAprons) {
    std::vector<float> dem(100 * 50);
    const RasterView v = RasterView::window(dem.data(), 100, 50, 100, 90, -5, 20, 20, 2, 3, 4);
    EXPECT_EQ(v.width, 10);
    EXPECT_EQ(v.height, 15);
    EXPECT_EQ(v.apronLeft, 4);
    EXPECT_EQ(v.apronTop, 0);
    EXPECT_EQ(v.apronRight, 0);
    EXPECT_EQ(v.apronBottom, 4);
    EXPECT_EQ(v.data, dem.data() + 90);
    EXPECT_TRUE(v.validate("x").empty());
    const RasterView outside = RasterView::window(dem.data(), 100, 50, 100, 200, 0, 5, 5, 1, 1);
    EXPECT_TRUE(outside.validate("tile 3/4/5").has("TOPO_INVALID_VIEW"));
    EXPECT_NE(outside.validate("tile 3/4/5").format().find("tile 3/4/5"), std::string::npos);
}

}  // namespace
}  // namespace kiosk::topo
