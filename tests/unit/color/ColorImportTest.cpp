#include "runtime/color/ColorImport.h"
#include "tests/unit/color/ColorTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

namespace kiosk::color {
namespace {

std::string paraviewFile() {
    return test::colorSharedData("colormaps/paraview/ColorMaps.json");
}

#define REQUIRE_FILE(path) \
    if ((path).empty()) GTEST_SKIP() << "shared data not found (set KIOSK_SHARED_DATA)"

TEST(ParaViewImport, RealFileHasTrailingCommaThatStrictJsonRejects) {
    const std::string file = paraviewFile();
    REQUIRE_FILE(file);
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    EXPECT_TRUE(nlohmann::json::parse(text, nullptr, false).is_discarded());
    EXPECT_EQ(stripTrailingCommas(text), 1u);
    const auto doc = nlohmann::json::parse(text, nullptr, false);
    ASSERT_FALSE(doc.is_discarded());
    EXPECT_EQ(doc.size(), 199u);
}

TEST(ParaViewImport, CoolToWarmIsDivergingMsh) {
    const std::string file = paraviewFile();
    REQUIRE_FILE(file);
    auto r = importParaViewFile(file, "Cool to Warm");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const auto& tf = *r.value;
    EXPECT_EQ(tf.space, Space::Msh);
    EXPECT_EQ(tf.stops.size(), 3u);
    EXPECT_EQ(tf.domainMin, 0.0);
    EXPECT_EQ(tf.domainMax, 1.0);
    EXPECT_EQ(tf.nodata, (Rgba{1, 1, 0, 1}));
    // The file's middle point is 0.865 grey = 220.6 DN; ends are (59, 76, 192), (180, 4, 38).
    const auto lut = buildLut(tf, 1024);
    auto mid = test::sampleLinear(lut, lutCoordinate(tf, 0.5, 1024));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mid[std::size_t(c)], 220.6, 1.0);
    auto a = test::sampleLinear(lut, lutCoordinate(tf, 0.0, 1024));
    EXPECT_NEAR(a[0], 59, 1.0);
    EXPECT_NEAR(a[2], 192, 1.0);
    // Between the stops: Msh keeps the blue side saturated-bluish, never purple.
    auto q = test::sampleLinear(lut, lutCoordinate(tf, 0.25, 1024));
    EXPECT_GT(q[2], q[0]);
}

TEST(ParaViewImport, NonNormalisedPointsKeepTheirRangeAndRescale) {
    const std::string file = paraviewFile();
    REQUIRE_FILE(file);
    auto r = importParaViewFile(file, "Blue Orange (divergent)");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_NEAR(r.value->domainMin, -30.3399130649763, 1e-9);
    EXPECT_NEAR(r.value->domainMax, 2.28518559486346, 1e-9);
    const TransferFunction scaled = r.value->rescaled(0, 10);
    EXPECT_EQ(scaled.stops.front().value, 0.0);
    EXPECT_DOUBLE_EQ(scaled.stops.back().value, 10.0);
    EXPECT_EQ(scaled.evaluate(0.0), r.value->evaluate(r.value->domainMin));

    auto cividis = importParaViewFile(file, "Cividis");  // x from 0 to 255
    ASSERT_TRUE(cividis.ok());
    EXPECT_EQ(cividis.value->domainMax, 255.0);
}

TEST(ParaViewImport, IndexedPresetBecomesClasses) {
    const std::string file = paraviewFile();
    REQUIRE_FILE(file);
    auto r = importParaViewFile(file, "KAAMS");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_TRUE(r.value->discrete());
    EXPECT_GT(r.value->classes.size(), 5u);
    EXPECT_EQ(r.value->classes[1].from, 1.0);
}

TEST(ParaViewImport, UnknownPresetSuggestsTheClosestName) {
    const std::string file = paraviewFile();
    REQUIRE_FILE(file);
    auto r = importParaViewFile(file, "Viridiss");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.diagnostics.firstError()->code, "COLOR_PARAVIEW_UNKNOWN_PRESET");
    EXPECT_EQ(r.diagnostics.firstError()->hint, "did you mean \"Viridis\"?");
}

// The built-in maps come from published control points; they must stay close to the reference
// 256-entry tables that ParaView ships (matplotlib's data).
TEST(NamedMaps, ViridisAndCividisTrackTheReferenceTables) {
    const std::string file = paraviewFile();
    REQUIRE_FILE(file);
    struct Case {
        const char* mine;
        const char* theirs;
        int tolerance;
    };
    for (const Case& c : {Case{"viridis", "Viridis", 2}, Case{"cividis", "Cividis", 5}}) {
        auto ref = importParaViewFile(file, c.theirs);
        ASSERT_TRUE(ref.ok());
        const TransferFunction refTf = ref.value->rescaled(0, 1);
        const TransferFunction tf = *namedMap(c.mine);
        int worst = 0;
        for (const auto& stop : refTf.stops) {
            const auto got = test::dn(tf.evaluate(stop.value));
            const auto want = test::dn(stop.color);
            for (int k = 0; k < 3; ++k)
                worst = std::max(worst, std::abs(got[std::size_t(k)] - want[std::size_t(k)]));
        }
        EXPECT_LE(worst, c.tolerance) << c.mine;
        EXPECT_GE(refTf.stops.size(), 256u);
    }
}

TEST(NamedMaps, FloodAndFire) {
    auto flood = namedMap("flood-depth");
    ASSERT_TRUE(flood);
    EXPECT_EQ(flood->units, "m");
    EXPECT_EQ(flood->domainMin, 0.0);
    EXPECT_EQ(flood->domainMax, 5.0);
    EXPECT_EQ(test::dn(flood->evaluate(0.0))[3], 0);  // dry is transparent
    EXPECT_EQ(test::dn(flood->evaluate(1.0))[3], 255);
    const auto shallow = test::dn(flood->evaluate(0.05)), deep = test::dn(flood->evaluate(5.0));
    EXPECT_GT(shallow[1], 200);  // light cyan
    EXPECT_LT(deep[0] + deep[1], 60);
    EXPECT_GT(deep[2], 80);  // deep blue
    auto fire = namedMap("fire-intensity");
    ASSERT_TRUE(fire);
    EXPECT_EQ(fire->units, "kW/m");
    const auto hot = test::dn(fire->evaluate(10000));
    EXPECT_GT(hot[0], 150);
    EXPECT_LT(hot[1], 30);
    EXPECT_FALSE(namedMap("virdis"));
    EXPECT_EQ(namedMapNames().size(), 5u);
}

TEST(ColorRelief, SrtmElevationClr) {
    const std::string file = test::colorSharedData("srtm90_osgearth/elevation.clr");
    REQUIRE_FILE(file);
    auto r = importColorReliefFile(file);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const auto& tf = *r.value;
    EXPECT_EQ(tf.space, Space::Srgb);
    ASSERT_EQ(tf.stops.size(), 5u);
    EXPECT_EQ(tf.domainMin, 0.0);
    EXPECT_EQ(tf.domainMax, 4000.0);
    // 900 m is half-way from (46, 154, 88) at 0 to (251, 255, 128) at 1800.
    const auto lut = buildLut(tf, 4001);
    const auto mid = test::sampleLinear(lut, lutCoordinate(tf, 900.0, 4001));
    EXPECT_NEAR(mid[0], 148.5, 1.0);
    EXPECT_NEAR(mid[1], 204.5, 1.0);
    EXPECT_NEAR(mid[2], 108.0, 1.0);
    for (const auto& s : tf.stops) {
        const auto got = test::sampleLinear(lut, lutCoordinate(tf, s.value, 4001));
        const auto want = test::dn(s.color);
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[std::size_t(c)], want[std::size_t(c)], 1.0);
    }
}

TEST(ColorRelief, GdalTestFiles) {
    const std::string desc = test::colorSharedData("colormaps/gdal_color_relief/color_file.txt");
    REQUIRE_FILE(desc);
    auto r = importColorReliefFile(desc);  // descending values, -32768 sentinel
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r.value->domainMin, -32768.0);
    EXPECT_EQ(r.value->domainMax, 500.0);
    EXPECT_EQ(test::dn(r.value->evaluate(75.0))[2], 255);
    EXPECT_EQ(test::dn(r.value->evaluate(500.0))[0], 255);

    auto nv = importColorReliefFile(
        test::colorSharedData("colormaps/gdal_color_relief/color_paletted_red_green_0-1-nv.txt"));
    ASSERT_TRUE(nv.ok()) << nv.diagnostics.format();
    EXPECT_EQ(nv.value->nodata, (Rgba{0, 0, 0, 0}));
    EXPECT_EQ(nv.value->stops.size(), 2u);

    auto pal = importColorReliefFile(
        test::colorSharedData("colormaps/gdal_color_relief/color_paletted_red_green_0-255.txt"));
    ASSERT_TRUE(pal.ok()) << pal.diagnostics.format();
    EXPECT_EQ(pal.value->stops.size(), 256u);
    EXPECT_EQ(test::dn(pal.value->stops[0].color)[3], 0);  // "0 255 255 255 0": alpha given
}

TEST(ColorRelief, PercentagesAndNames) {
    auto r =
        parseColorRelief("0% black\n50%, 255, 0, 0\n100%:white\n", "p.clr", std::pair{10.0, 20.0});
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r.value->stops[1].value, 15.0);
    EXPECT_EQ(r.value->domainMax, 20.0);
    EXPECT_EQ(test::dn(r.value->evaluate(15.0))[0], 255);
}

struct BadClr {
    const char* name;
    const char* text;
    const char* code;
    int line;
    const char* message;
};

TEST(ColorRelief, BadInputsReportCodeAndLine) {
    const BadClr cases[] = {
        {"bad value", "0 0 0 0\nabc 1 2 3\n", "COLOR_CLR_SYNTAX", 2, "bad value \"abc\""},
        {"component range", "0 1 2 300\n1 0 0 0\n", "COLOR_CLR_RANGE", 1, "outside 0..255"},
        {"three fields", "0 1 2\n", "COLOR_CLR_SYNTAX", 1, "got 3 fields"},
        {"float component", "0 1 2.5 3\n", "COLOR_CLR_SYNTAX", 1, "not an integer"},
        {"unknown name", "0 reed\n1 blue\n", "COLOR_CLR_SYNTAX", 1, "unknown colour name"},
        {"percent without range", "0% 0 0 0\n100% 1 1 1\n", "COLOR_CLR_PERCENT", 1,
         "needs the data range"},
        {"one entry", "0 0 0 0\n", "COLOR_CLR_EMPTY", 0, "at least two"},
        {"empty", "", "COLOR_CLR_EMPTY", 0, "at least two"},
    };
    for (const auto& c : cases) {
        auto r = parseColorRelief(c.text, "bad.clr");
        ASSERT_FALSE(r.ok()) << c.name;
        const Diagnostic* e = r.diagnostics.firstError();
        EXPECT_EQ(e->code, c.code) << c.name;
        EXPECT_EQ(e->line, c.line) << c.name;
        EXPECT_NE(e->format().find(c.message), std::string::npos) << c.name << ": " << e->format();
        EXPECT_EQ(e->file, "bad.clr");
    }
}

struct BadPv {
    const char* name;
    const char* text;
    const char* code;
};

TEST(ParaViewImport, BadInputsReportCodes) {
    const BadPv cases[] = {
        {"not json", "{{", "COLOR_PARAVIEW_PARSE"},
        {"scalar", "3", "COLOR_PARAVIEW_PARSE"},
        {"missing", R"([{"Name":"other","RGBPoints":[0,0,0,0,1,1,1,1]}])",
         "COLOR_PARAVIEW_UNKNOWN_PRESET"},
        {"short points", R"([{"Name":"x","RGBPoints":[0,1,1]}])", "COLOR_PARAVIEW_POINTS"},
        {"channel > 1", R"([{"Name":"x","RGBPoints":[0,2,0,0,1,1,1,1]}])", "COLOR_PARAVIEW_POINTS"},
        {"string x", R"([{"Name":"x","RGBPoints":["a",0,0,0,1,1,1,1]}])", "COLOR_PARAVIEW_POINTS"},
        {"no points", R"([{"Name":"x"}])", "COLOR_PARAVIEW_POINTS"},
        {"single x", R"([{"Name":"x","RGBPoints":[1,0,0,0,1,1,1,1]}])", "TF_DOMAIN"},
    };
    for (const auto& c : cases) {
        auto r = importParaView(c.text, "x", "p.json");
        ASSERT_FALSE(r.ok()) << c.name;
        EXPECT_EQ(r.diagnostics.firstError()->code, c.code)
            << c.name << ": " << r.diagnostics.format();
    }
    // Trailing commas inside and after presets are tolerated deliberately.
    auto ok = importParaView(
        R"([{"Name":"x","ColorSpace":"RGB","RGBPoints":[0,0,0,0,2,1,1,1,],},])", "x", "p.json");
    ASSERT_TRUE(ok.ok()) << ok.diagnostics.format();
    EXPECT_EQ(ok.value->space, Space::Srgb);
    EXPECT_EQ(test::dn(ok.value->evaluate(1.0))[0], 128);
    auto hsv = importParaView(R"([{"Name":"x","ColorSpace":"HSV","RGBPoints":[0,0,0,0,2,1,1,1]}])",
                              "x", "p.json");
    ASSERT_TRUE(hsv.ok());
    EXPECT_TRUE(hsv.diagnostics.has("COLOR_PARAVIEW_SPACE"));
}

}  // namespace
}  // namespace kiosk::color
