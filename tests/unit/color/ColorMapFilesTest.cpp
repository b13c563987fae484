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
    auto hsv = parseCpt("# COLOR_MODEL = HSV\n0 0-1-1 1 120-1-1\n", "hsv.cpt");
    ASSERT_FALSE(hsv.ok());
    EXPECT_EQ(hsv.diagnostics.firstError()->code, "COLOR_CPT_UNSUPPORTED");
    EXPECT_EQ(hsv.diagnostics.firstError()->line, 1);
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
