// Pixel comparison of kiosk::topo::hillshade with `gdaldem hillshade` (GDAL 3.6) on the real
// DEMs of ../shared/data. The test runs gdaldem itself into a temporary directory; it skips
// with a message when gdaldem or the data is absent.

#include "runtime/topo/Hillshade.h"
#include "tests/unit/topo/GdalFixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace kiosk::topo {
namespace {

using test::ByteRaster;
using test::FloatRaster;

struct Comparison {
    long long nodataMismatch = 0;  ///< one side nodata (0), the other not
    long long beyondOne = 0;       ///< |ours - gdal| > 1
    int maxDiff = 0;
    long long valid = 0;  ///< pixels both sides shade (not nodata)
    long long exact = 0;  ///< identical bytes
    std::string firstBad;
};

Comparison compare(const std::vector<std::uint8_t>& ours, const ByteRaster& gdal) {
    Comparison c;
    for (int r = 0; r < gdal.height; ++r) {
        for (int col = 0; col < gdal.width; ++col) {
            const std::size_t i = static_cast<std::size_t>(r) * gdal.width + col;
            const int a = ours[i];
            const int b = gdal.values[i];
            const bool bad = (a == 0) != (b == 0) || std::abs(a - b) > 1;
            if ((a == 0) != (b == 0))
                ++c.nodataMismatch;
            else if (std::abs(a - b) > 1)
                ++c.beyondOne;
            if (a != 0 && b != 0) ++c.valid;
            if (a == b) ++c.exact;
            c.maxDiff = std::max(c.maxDiff, std::abs(a - b));
            if (bad && c.firstBad.empty())
                c.firstBad = "(" + std::to_string(col) + "," + std::to_string(r) + "): ours " +
                             std::to_string(a) + ", gdaldem " + std::to_string(b);
        }
    }
    return c;
}

struct Case {
    const char* name;
    const char* data;  ///< file under ../shared/data
    const char* gdalArgs;
    HillshadeParams params;
    bool puget;  ///< the non-georeferenced heightmap: georeference it first (160 m, north-up)
};

HillshadeParams make(HillshadeVariant v, bool edges, double scale, double z,
                     GradientAlgorithm alg = GradientAlgorithm::Horn, double az = 315,
                     double alt = 45) {
    HillshadeParams p;
    p.variant = v;
    p.computeEdges = edges;
    p.scale = scale;
    p.zFactor = z;
    p.algorithm = alg;
    p.azimuthDeg = az;
    p.altitudeDeg = alt;
    return p;
}

constexpr const char* kRainier = "srtm90_osgearth/mt_rainier_90m.tif";
constexpr const char* kPuget = "puget_sound_heightmap/ps_height_1k.png";
using V = HillshadeVariant;
using A = GradientAlgorithm;

const Case kCases[] = {
    {"RainierDefault", kRainier, "-s 111120", make(V::Default, false, 111120, 1), false},
    {"RainierDefaultEdges", kRainier, "-s 111120 -compute_edges", make(V::Default, true, 111120, 1),
     false},
    {"RainierMultidirectional", kRainier, "-s 111120 -multidirectional",
     make(V::Multidirectional, false, 111120, 1), false},
    {"RainierMultidirectionalEdges", kRainier, "-s 111120 -multidirectional -compute_edges",
     make(V::Multidirectional, true, 111120, 1), false},
    {"RainierCombined", kRainier, "-s 111120 -combined", make(V::Combined, false, 111120, 1),
     false},
    {"RainierCombinedEdges", kRainier, "-s 111120 -combined -compute_edges",
     make(V::Combined, true, 111120, 1), false},
    {"RainierZevenbergenThorne", kRainier, "-s 111120 -alg ZevenbergenThorne -compute_edges",
     make(V::Default, true, 111120, 1, A::ZevenbergenThorne), false},
    {"RainierLowSunExaggerated", kRainier, "-s 111120 -z 3 -az 120 -alt 20",
     make(V::Default, false, 111120, 3, A::Horn, 120, 20), false},
    {"PugetDefault", kPuget, "-z 0.1", make(V::Default, false, 1, 0.1), true},
    {"PugetDefaultEdges", kPuget, "-z 0.1 -compute_edges", make(V::Default, true, 1, 0.1), true},
    {"PugetMultidirectional", kPuget, "-z 0.1 -multidirectional -compute_edges",
     make(V::Multidirectional, true, 1, 0.1), true},
    {"PugetCombined", kPuget, "-z 0.1 -combined -compute_edges", make(V::Combined, true, 1, 0.1),
     true},
    {"PugetZevenbergenThorneMulti", kPuget,
     "-z 0.1 -alg ZevenbergenThorne -multidirectional -alt 30",
     make(V::Multidirectional, false, 1, 0.1, A::ZevenbergenThorne, 315, 30), true},
};

class HillshadeGdalTest : public ::testing::TestWithParam<Case> {
protected:
    void SetUp() override {
        if (test::gdaldemPath().empty())
            GTEST_SKIP() << "gdaldem not installed (Debian package gdal-bin); comparison skipped";
        mDir = test::makeTempDir();
        ASSERT_FALSE(mDir.empty()) << "cannot create a temporary directory";
    }
    void TearDown() override { test::removeDir(mDir); }

    std::string mDir;
};

TEST_P(HillshadeGdalTest, MatchesGdaldemWithinOneDn) {
    const Case& tc = GetParam();
    const std::string src = test::sharedData(tc.data);
    if (src.empty()) GTEST_SKIP() << "shared data " << tc.data << " absent (KIOSK_SHARED_DATA)";

    std::string error;
    auto dem = test::readFloat(src, error);
    ASSERT_TRUE(dem) << error;
    std::string input = src;
    if (tc.puget) {
        // The PNG has no georeferencing: GDAL then assumes a +1 row step (rows running
        // north), which mirrors the light. Give it the real layout, 160 m north-up, as the
        // importer will.
        dem->geoTransform[0] = 0;
        dem->geoTransform[1] = 160;
        dem->geoTransform[3] = 160.0 * dem->height;
        dem->geoTransform[5] = -160;
        input = mDir + "/puget.tif";
        ASSERT_TRUE(test::writeFloatTiff(input, *dem, error)) << error;
    }
    const std::string out = mDir + "/gdal.tif";
    ASSERT_EQ(test::runGdaldem(tc.gdalArgs, input, out), 0) << "gdaldem " << tc.gdalArgs;
    auto gdal = test::readByte(out, error);
    ASSERT_TRUE(gdal) << error;
    ASSERT_EQ(gdal->width, dem->width);
    ASSERT_EQ(gdal->height, dem->height);

    const RasterView view =
        RasterView::window(dem->values.data(), dem->width, dem->height, dem->width, 0, 0,
                           dem->width, dem->height, dem->geoTransform[1], -dem->geoTransform[5]);
    std::vector<std::uint8_t> ours(dem->values.size(), 77);
    const Diagnostics d = hillshade(view, tc.params, ours.data(), dem->width);
    ASSERT_FALSE(d.hasErrors()) << d.format();

    const Comparison c = compare(ours, *gdal);
    EXPECT_EQ(c.nodataMismatch, 0) << "first: " << c.firstBad;
    EXPECT_EQ(c.beyondOne, 0) << "max diff " << c.maxDiff << ", first: " << c.firstBad;
    // Guard against comparing two blank images.
    EXPECT_GT(c.valid, static_cast<long long>(dem->values.size()) * 9 / 10);
    std::printf("[ stats    ] %s: %lld of %zu pixels identical, max |diff| %d\n", tc.name, c.exact,
                dem->values.size(), c.maxDiff);
}

// The comparison must be able to fail: a 10 degree azimuth error is far outside +-1 DN.
TEST_F(HillshadeGdalTest, ComparisonDetectsAWrongAzimuth) {
    const std::string src = test::sharedData(kRainier);
    if (src.empty()) GTEST_SKIP() << "shared data " << kRainier << " absent (KIOSK_SHARED_DATA)";
    std::string error;
    auto dem = test::readFloat(src, error);
    ASSERT_TRUE(dem) << error;
    const std::string out = mDir + "/gdal.tif";
    ASSERT_EQ(test::runGdaldem("-s 111120", src, out), 0);
    auto gdal = test::readByte(out, error);
    ASSERT_TRUE(gdal) << error;
    const RasterView view =
        RasterView::window(dem->values.data(), dem->width, dem->height, dem->width, 0, 0,
                           dem->width, dem->height, dem->geoTransform[1], -dem->geoTransform[5]);
    std::vector<std::uint8_t> ours(dem->values.size());
    ASSERT_FALSE(hillshade(view, make(V::Default, false, 111120, 1, A::Horn, 325, 45), ours.data(),
                           dem->width)
                     .hasErrors());
    EXPECT_GT(compare(ours, *gdal).beyondOne, static_cast<long long>(dem->values.size()) / 10);
}

INSTANTIATE_TEST_SUITE_P(RealDems, HillshadeGdalTest, ::testing::ValuesIn(kCases),
                         [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace kiosk::topo
