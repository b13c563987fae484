// The shipped projective-mapping scenarios (issue 8) rendered by the geokiosk binary from their
// top-down viewpoint, compared with the same scenario without mappings: each mapping shows
// where it was placed, the rest of the picture is untouched (or dimmed, for focus+context), and
// --stats counts active and culled mappings.
#include "runtime/math/Camera.h"
#include "tests/support/EglTestContext.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

namespace kiosk {
namespace {

namespace fs = std::filesystem;
constexpr int kW = 480, kH = 270;

struct Picture {
    int w = 0, h = 0;
    std::vector<std::uint8_t> rgb;
    glm::ivec3 at(int x, int y) const {
        x = std::clamp(x, 0, w - 1);
        y = std::clamp(y, 0, h - 1);
        const auto* p = &rgb[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3];
        return {p[0], p[1], p[2]};
    }
};

Picture readPng(const fs::path& file) {
    Picture p;
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) return p;
    p.w = in->spec().width;
    p.h = in->spec().height;
    p.rgb.resize(std::size_t(p.w) * std::size_t(p.h) * 3);
    in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, p.rgb.data());
    return p;
}

class MappingScenarioTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists("data/generated/rainier.gpkg"))
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA",
                               "demo store missing: run tools/prepare-demo.sh");
        mDir = fs::temp_directory_path() / ("kiosk-mappings-" + std::to_string(::getpid()));
        fs::create_directories(mDir);
    }
    void TearDown() override {
        std::error_code ec;
        if (!mDir.empty()) fs::remove_all(mDir, ec);
    }

    /** Render `scenario` (and, with plain, a copy without mappings) at `time` from "top". */
    Picture render(const std::string& name, bool plain, nlohmann::json* stats = nullptr,
                   const std::string& time = "+15m") {
        fs::path scenario = fs::absolute("scenarios/mappings/" + name + ".json");
        if (plain) {
            const fs::path copy = mDir / (name + "-plain.json");
            std::ofstream(copy) << nlohmann::json{{"version", 1},
                                                  {"include", {scenario.string()}},
                                                  {"projectiveMappings", nlohmann::json::array()}};
            scenario = copy;
        }
        const fs::path out = mDir / (name + (plain ? "-plain.png" : ".png"));
        const fs::path st = mDir / (name + ".stats.json");
        const std::string cmd = std::string(KIOSK_GEOKIOSK_BIN) + " render '" + scenario.string() +
                                "' --out '" + out.string() + "' --size " + std::to_string(kW) +
                                "x" + std::to_string(kH) + " --time " + time +
                                " --viewpoint top --stats '" + st.string() + "'";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
        if (stats) *stats = nlohmann::json::parse(std::ifstream(st), nullptr, false);
        return readPng(out);
    }

    /** Pixel of a world point seen from the scenario's "top" viewpoint (terrain at target z). */
    static glm::ivec2 pixelOf(const math::Viewpoint& vp, glm::dvec2 world) {
        const auto cam = math::Camera::fromViewpoint(vp, kW, kH, 45.0);
        const glm::dvec4 c = cam.projection() * cam.view() * glm::dvec4(world, vp.target.z, 1.0);
        const glm::dvec2 ndc(c.x / c.w, c.y / c.w);
        return {int((ndc.x * 0.5 + 0.5) * kW), int((0.5 - ndc.y * 0.5) * kH)};
    }

    /** True if some pixel within `r` of p satisfies pred. */
    static bool near(const Picture& img, glm::ivec2 p, int r,
                     const std::function<bool(glm::ivec3)>& pred) {
        for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx)
                if (pred(img.at(p.x + dx, p.y + dy))) return true;
        return false;
    }

    static int diff(glm::ivec3 a, glm::ivec3 b) {
        return std::abs(a.x - b.x) + std::abs(a.y - b.y) + std::abs(a.z - b.z);
    }

    fs::path mDir;
};

TEST_F(MappingScenarioTest, RouteIsHighlightedAndContextDimmed) {
    nlohmann::json stats;
    const Picture on = render("route", false, &stats);
    const Picture off = render("route", true);
    ASSERT_EQ(on.w, kW);
    ASSERT_EQ(off.w, kW);
    const math::Viewpoint top{{595000, 5178000, 1000}, 0, -89.9, 40000};
    // Middle of the second edge and the third way point: route red over the terrain.
    auto red = [](glm::ivec3 c) { return c.r > 150 && c.r > 2 * c.g && c.r > 2 * c.b; };
    for (glm::dvec2 w : {glm::dvec2(592000, 5177000), glm::dvec2(596000, 5176000)}) {
        const auto p = pixelOf(top, w);
        EXPECT_TRUE(near(on, p, 6, red)) << "no route at pixel " << p.x << "," << p.y;
        EXPECT_FALSE(near(off, p, 6, red)) << "plain render is already red there";
    }
    // The context (away from the route) keeps half its brightness.
    double sumOn = 0, sumOff = 0;
    const auto corner = pixelOf(top, {605000, 5168000});  // below the title overlay
    for (int y = corner.y - 10; y <= corner.y + 10; ++y)
        for (int x = corner.x - 10; x <= corner.x + 10; ++x) {
            const auto a = on.at(x, y), b = off.at(x, y);
            sumOn += a.r + a.g + a.b;
            sumOff += b.r + b.g + b.b;
        }
    EXPECT_NEAR(sumOn / sumOff, 0.5, 0.03);
    ASSERT_TRUE(stats.is_object());
    EXPECT_EQ(stats["frames"]["mappings_active"][0], 9);  // 4 edges + 5 way points
}

TEST_F(MappingScenarioTest, SymbolsAppearWhereTheyArePlacedAndCullingIsCounted) {
    nlohmann::json stats;
    const Picture on = render("symbols", false, &stats);
    const Picture off = render("symbols", true);
    ASSERT_EQ(on.w, kW);
    const math::Viewpoint top{{596000, 5181000, 1000}, 0, -89.9, 40000};
    auto blue = [](glm::ivec3 c) { return c.b > 150 && c.r < 100; };
    auto orange = [](glm::ivec3 c) { return c.r > 200 && c.g > 90 && c.g < 190 && c.b < 60; };
    EXPECT_TRUE(near(on, pixelOf(top, {601000, 5176000}), 5, blue)) << "shelter";
    EXPECT_FALSE(near(off, pixelOf(top, {601000, 5176000}), 5, blue));
    EXPECT_TRUE(near(on, pixelOf(top, {604000, 5190000}), 5, orange)) << "lookout";
    EXPECT_FALSE(near(off, pixelOf(top, {604000, 5190000}), 5, orange));
    for (glm::dvec2 w : {glm::dvec2(588000, 5186000), glm::dvec2(590000, 5172000)}) {
        const auto p = pixelOf(top, w);
        EXPECT_GT(diff(on.at(p.x, p.y), off.at(p.x, p.y)), 60) << "symbol missing at " << p.x;
    }
    // Far from every symbol the picture is unchanged.
    const auto empty = pixelOf(top, {580000, 5180000});
    EXPECT_LE(diff(on.at(empty.x, empty.y), off.at(empty.x, empty.y)), 3);
    ASSERT_TRUE(stats.is_object());
    EXPECT_EQ(stats["frames"]["mappings_active"][0], 4);
    EXPECT_EQ(stats["frames"]["mappings_culled_frustum"][0], 1);  // far-camp, 80 km south
    EXPECT_EQ(stats["frames"]["mappings_culled_size"][0], 1);     // 3 m survey marker
}

// The mapping shows the live maximum depth so far (a layer of the stack): deep red where the
// SYNTHETIC flood has been deep by the end of the run, not yet early in the run.
TEST_F(MappingScenarioTest, HazardZoneColoursTheFloodThroughItsTransferFunction) {
    nlohmann::json stats;
    const Picture on = render("hazard", false, &stats, "+9h");
    const Picture off = render("hazard", true, nullptr, "+9h");
    const Picture early = render("hazard", false, nullptr, "+15m");
    ASSERT_EQ(on.w, kW);
    const math::Viewpoint top{{592000, 5158000, 600}, 0, -89.9, 50000};
    auto red = [](glm::ivec3 c) { return c.r > 80 && c.r > 2 * c.g && c.r > 2 * c.b; };
    for (glm::dvec2 w : {glm::dvec2(580374, 5151607), glm::dvec2(603477, 5165993)}) {
        const auto p = pixelOf(top, w);
        EXPECT_TRUE(near(on, p, 3, red)) << "no hazard colour at " << p.x << "," << p.y;
        EXPECT_FALSE(near(off, p, 3, red));
        EXPECT_FALSE(near(early, p, 3, red)) << "deep at +15m: not the live maximum so far";
    }
    // Outside the mapping's rectangle (north of it) nothing changes.
    const auto outside = pixelOf(top, {592000, 5178000});
    EXPECT_LE(diff(on.at(outside.x, outside.y), off.at(outside.x, outside.y)), 3);
    ASSERT_TRUE(stats.is_object());
    EXPECT_EQ(stats["frames"]["mappings_active"][0], 1);
}

TEST_F(MappingScenarioTest, FocusKeepsColourAndContextTurnsGrey) {
    const Picture on = render("focus", false);
    const Picture off = render("focus", true);
    ASSERT_EQ(on.w, kW);
    const math::Viewpoint top{{595000, 5181000, 1000}, 0, -89.9, 40000};
    // At +15m the focus has moved a quarter of the way to its last key.
    const auto inside = pixelOf(top, {593000, 5183250});
    EXPECT_LE(diff(on.at(inside.x, inside.y), off.at(inside.x, inside.y)), 6);
    const auto ctx = pixelOf(top, {610000, 5170000});
    const auto g = on.at(ctx.x, ctx.y), o = off.at(ctx.x, ctx.y);
    EXPECT_LE(std::abs(g.r - g.g) + std::abs(g.g - g.b), 3) << "context not grey";
    EXPECT_LT(g.r + g.g + g.b, o.r + o.g + o.b) << "context not dimmed";
}

}  // namespace
}  // namespace kiosk
