// Colour-map files users have: cmocean/matplotlib float RGB lists, GMT .cpt (continuous with
// B/F/N, categorical), GRASS colour rules with `default`, each written here; a broken file of
// each kind gives exactly one error, with its line.
#include "runtime/color/ColorImport.h"
#include "runtime/color/ColorMapFiles.h"
#include "tests/unit/color/ColorTestSupport.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace kiosk::color {
namespace {

std::filesystem::path writeFile(const std::string& name, const std::string& text) {
    const auto dir = std::filesystem::temp_directory_path() / "geokiosk-colormap-test";
    std::filesystem::create_directories(dir);
    const auto p = dir / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

std::size_t errorCount(const Diagnostics& d) {
    std::size_t n = 0;
    for (const auto& i : d.items()) n += i.severity == Severity::Error;
    return n;
}

TEST(ColorMapFiles, CmoceanFloatRgbListSpreadsEvenlyOnZeroToOne) {
    // The head of cmocean's thermal-rgb.txt layout: `%.18e %.18e %.18e` rows (np.savetxt).
    std::string text;
    for (int i = 0; i < 256; ++i) {
        char row[128];
        const double t = i / 255.0;
        std::snprintf(row, sizeof row, "%.18e %.18e %.18e\n", t, 0.5 * t, 1.0 - t);
        text += row;
    }
    const auto file = writeFile("thermal-rgb.txt", text);
    EXPECT_EQ(sniffColorFile(file, text), ColorFileFormat::FloatRgb);
    auto r = importColorMapFile(file);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r->stops.size(), 256u);
    EXPECT_DOUBLE_EQ(r->domainMin, 0.0);
    EXPECT_DOUBLE_EQ(r->domainMax, 1.0);
    const auto mid = test::dn(r->evaluate(128.0 / 255.0));
    EXPECT_EQ(mid[0], 128);
    EXPECT_EQ(mid[1], 64);
    EXPECT_EQ(mid[2], 127);
}

TEST(ColorMapFiles, BrokenFloatListGivesOneErrorWithItsLine) {
    std::string text;
    for (int i = 0; i < 256; ++i) text += "0.1 0.2 " + std::string(i == 3 ? "1.7" : "0.3") + "\n";
    text += "0.5 0.5\n";  // a second problem further down is not reported again
    auto r = parseFloatRgbList(text, "bad-rgb.txt");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(errorCount(r.diagnostics), 1u) << r.diagnostics.format();
    EXPECT_EQ(r.diagnostics.firstError()->code, "COLOR_RGB_RANGE");
    EXPECT_EQ(r.diagnostics.firstError()->line, 4);
}

TEST(ColorMapFiles, GmtCptWithSlashColoursAndBackgroundForegroundNan) {
    const std::string text =
        "# cpt written by hand\n"
        "# COLOR_MODEL = RGB\n"
        "0\t0/0/255\t10\t0/255/0\n"
        "10\t0/255/0\t20\t255/0/0 U\n"
        "B\tblack\n"
        "F\t255/255/255\n"
        "N\t128\n";
    const auto file = writeFile("relief.cpt", text);
    auto r = importColorMapFile(file);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const TransferFunction& tf = *r.value;
    EXPECT_DOUBLE_EQ(tf.domainMin, 0.0);
    EXPECT_DOUBLE_EQ(tf.domainMax, 20.0);
    EXPECT_EQ(test::dn(tf.evaluate(5.0)), (std::array<int, 4>{0, 128, 128, 255}));
    EXPECT_EQ(test::dn(tf.shade(-1.0)), (std::array<int, 4>{0, 0, 0, 255}));        // B
    EXPECT_EQ(test::dn(tf.shade(25.0)), (std::array<int, 4>{255, 255, 255, 255}));  // F
    EXPECT_EQ(test::dn(tf.shade(std::nan(""))), (std::array<int, 4>{128, 128, 128, 255}));
}

TEST(ColorMapFiles, GmtCpt4SpaceSeparatedAndStepBetweenSlices) {
    const std::string text =
        "-100 0 0 255 0 0 0 255\n"  // GMT 4: z r g b z r g b
        "0 255 255 0 100 255 0 0\n";
    auto r = parseCpt(text, "steps.cpt");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(test::dn(r->evaluate(-50)), (std::array<int, 4>{0, 0, 255, 255}));
    EXPECT_EQ(test::dn(r->evaluate(50)), (std::array<int, 4>{255, 128, 0, 255}));
}

TEST(ColorMapFiles, CategoricalCptKeepsLabels) {
    const std::string text =
        "1\tred\t;Burnt\n"
        "2\t#00ff00\t;Burning\n"
        "3\t0/0/255\t;Unburnt\n";
    auto r = parseCpt(text, "fire.cpt");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    ASSERT_EQ(r->classes.size(), 3u);
    EXPECT_EQ(r->classes[1].label, "Burning");
    EXPECT_EQ(test::dn(r->evaluate(2.0)), (std::array<int, 4>{0, 255, 0, 255}));
    EXPECT_EQ(test::dn(r->evaluate(3.0)), (std::array<int, 4>{0, 0, 255, 255}));
}

TEST(ColorMapFiles, BrokenCptGivesOneErrorWithItsLine) {
    auto r = parseCpt("0 0/0/0 10 0/0/0\n10 0/0/400 20 1/2/3\n20 x 30 y\n", "bad.cpt");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(errorCount(r.diagnostics), 1u) << r.diagnostics.format();
    EXPECT_EQ(r.diagnostics.firstError()->code, "COLOR_CPT_SYNTAX");
    EXPECT_EQ(r.diagnostics.firstError()->line, 2);
    auto cmyk = parseCpt("# COLOR_MODEL = CMYK\n0 0/0/0/1 1 1/0/0/0\n", "cmyk.cpt");
    ASSERT_FALSE(cmyk.ok());
    EXPECT_EQ(cmyk.diagnostics.firstError()->code, "COLOR_CPT_UNSUPPORTED");
    EXPECT_EQ(cmyk.diagnostics.firstError()->line, 1);
    auto hue = parseCpt("# COLOR_MODEL = hsv\n0 0-1-1 1 120-1-1\n1 120-1-1 2 400-1-1\n", "h.cpt");
    ASSERT_FALSE(hue.ok());
    EXPECT_EQ(hue.diagnostics.firstError()->code, "COLOR_CPT_SYNTAX");
    EXPECT_EQ(hue.diagnostics.firstError()->line, 3);
    auto name = parseCpt("0 gray80 1 grey101\n", "n.cpt");
    ASSERT_FALSE(name.ok());
    EXPECT_EQ(name.diagnostics.firstError()->code, "COLOR_CPT_SYNTAX");
    EXPECT_EQ(name.diagnostics.firstError()->line, 1);
}

// The names gmt-common's palettes use, and GMT's own additions; values from GMT's colour table
// (X11's: gray is 190 and green 0/255/0 there, not CSS's 128).
TEST(ColorMapFiles, GmtColourNamesTakeGmtValues) {
    const std::string text =
        "0\tmediumaquamarine\t1\tgray80\n"
        "1\tdarkorange1\t2\tMediumSeaGreen\n"
        "2\tgray\t3\tgreen\n"
        "3\tlightred\t4\tgrey0\n"
        "B\tnavyblue\n"
        "F\tdarkyellow\n"
        "N\tgray50\n";
    const auto file = writeFile("named.cpt", text);
    auto r = importColorMapFile(file);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const TransferFunction& tf = *r.value;
    using C = std::array<int, 4>;
    ASSERT_EQ(tf.stops.size(), 8u);
    EXPECT_EQ(test::dn(tf.stops[0].color), (C{102, 205, 170, 255}));
    EXPECT_EQ(test::dn(tf.stops[1].color), (C{204, 204, 204, 255}));
    EXPECT_EQ(test::dn(tf.stops[2].color), (C{255, 127, 0, 255}));
    EXPECT_EQ(test::dn(tf.stops[3].color), (C{60, 179, 113, 255}));
    EXPECT_EQ(test::dn(tf.stops[4].color), (C{190, 190, 190, 255}));
    EXPECT_EQ(test::dn(tf.stops[5].color), (C{0, 255, 0, 255}));
    EXPECT_EQ(test::dn(tf.stops[6].color), (C{255, 128, 128, 255}));
    EXPECT_EQ(test::dn(tf.stops[7].color), (C{0, 0, 0, 255}));
    EXPECT_EQ(test::dn(tf.shade(-1.0)), (C{0, 0, 128, 255}));
    EXPECT_EQ(test::dn(tf.shade(9.0)), (C{128, 128, 0, 255}));
    EXPECT_EQ(test::dn(tf.shade(std::nan(""))), (C{127, 127, 127, 255}));
}

// GMT's rainbow.cpt layout (`h-s-v` colours, GMT 5/6) and GMT 4's `z h s v z h s v`: slices are
// interpolated in HSV, so the midpoints are GMT's hsv-to-rgb of the interpolated h, s, v.
TEST(ColorMapFiles, HsvCptInterpolatesInHsvLikeGmt) {
    const std::string text =
        "# COLOR_MODEL = hsv\n"
        "0\t300-1-1\t1\t240-1-1\n"
        "1\t240-1-1\t2\t0-1-1\n"
        "2 0 0 1 3 120 1 0.5\n"
        "B\t0-0-0\n"
        "F\t60 1 1\n"
        "N\t128\n";
    const auto file = writeFile("rainbow.cpt", text);
    auto r = importColorMapFile(file);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const TransferFunction& tf = *r.value;
    using C = std::array<int, 4>;
    EXPECT_DOUBLE_EQ(tf.domainMin, 0.0);
    EXPECT_DOUBLE_EQ(tf.domainMax, 3.0);
    EXPECT_EQ(test::dn(tf.evaluate(0.0)), (C{255, 0, 255, 255}));   // h 300
    EXPECT_EQ(test::dn(tf.evaluate(0.25)), (C{191, 0, 255, 255}));  // h 285
    EXPECT_EQ(test::dn(tf.evaluate(1.0)), (C{0, 0, 255, 255}));     // h 240
    // Through cyan, green and yellow: hue 240 down to 0 crosses four sextants.
    EXPECT_EQ(test::dn(tf.evaluate(1.25)), (C{0, 255, 255, 255}));   // h 180
    EXPECT_EQ(test::dn(tf.evaluate(1.375)), (C{0, 255, 128, 255}));  // h 150
    EXPECT_EQ(test::dn(tf.evaluate(1.5)), (C{0, 255, 0, 255}));      // h 120
    EXPECT_EQ(test::dn(tf.evaluate(1.75)), (C{255, 255, 0, 255}));   // h 60
    EXPECT_EQ(test::dn(tf.evaluate(1.9)), (C{255, 102, 0, 255}));    // h 24
    // s and v change too: h 60, s 0.5, v 0.75 halfway; within 1 DN between the sub-stops.
    EXPECT_EQ(test::dn(tf.evaluate(2.5)), (C{191, 191, 96, 255}));
    const C at = test::dn(tf.evaluate(2.3));  // h 36, s 0.3, v 0.85
    const C gmt{217, 191, 152, 255};
    for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(at[k], gmt[k], 1) << k;
    EXPECT_EQ(test::dn(tf.shade(-1.0)), (C{0, 0, 0, 255}));
    EXPECT_EQ(test::dn(tf.shade(4.0)), (C{255, 255, 0, 255}));
    EXPECT_EQ(test::dn(tf.shade(std::nan(""))), (C{128, 128, 128, 255}));
}

TEST(ColorMapFiles, GrassRulesWithDefaultAndPercent) {
    const std::string text =
        "% 0 100\n"  // r.colors min/max line: not a rule
        "0% blue\n"
        "50% 0:255:0\n"
        "100% red\n"
        "nv 255 255 255\n"
        "default 64:64:64\n";
    const auto file = writeFile("depth.rules", text);
    EXPECT_EQ(sniffColorFile(file, text), ColorFileFormat::ColorRules);
    auto r = importColorMapFile(file, std::pair{0.0, 10.0});
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(test::dn(r->evaluate(5.0)), (std::array<int, 4>{0, 255, 0, 255}));
    EXPECT_EQ(test::dn(r->shade(-3.0)), (std::array<int, 4>{64, 64, 64, 255}));
    EXPECT_EQ(test::dn(r->shade(11.0)), (std::array<int, 4>{64, 64, 64, 255}));
    EXPECT_EQ(test::dn(r->shade(std::nan(""))), (std::array<int, 4>{255, 255, 255, 255}));
}

TEST(ColorMapFiles, BrokenRulesGiveOneErrorWithItsLine) {
    std::string text = "0 0 0 0\n";
    for (int i = 1; i < 50; ++i) text += std::to_string(i) + " 0/0/4\n";  // GMT-style colour
    auto r = parseColorRelief(text, "x.txt");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(errorCount(r.diagnostics), 1u) << r.diagnostics.format();
    EXPECT_EQ(r.diagnostics.firstError()->line, 2);
}

TEST(ColorMapFiles, SingleParaViewPresetByFileAlone) {
    const std::string one =
        R"([{"Name": "two", "ColorSpace": "RGB", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]}])";
    auto r = importColorMapFile(writeFile("one.json", one));
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r->stops.size(), 2u);
    const std::string two =
        R"([{"Name": "a", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]},
            {"Name": "b", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]}])";
    auto many = importColorMapFile(writeFile("two.json", two));
    ASSERT_FALSE(many.ok());
    EXPECT_NE(many.diagnostics.firstError()->message.find("2 presets"), std::string::npos);
}

}  // namespace
}  // namespace kiosk::color
