// Briefings exported by the geokiosk binary (issue 18): a two-chapter scenario over the demo
// renders chapter 2 with its own viewpoint, layer override and caption, holds a pausing
// chapter's last frame, and an MP4 export carries the chapters as markers ffprobe lists.
#include "tests/support/EglTestContext.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace kiosk {
namespace {

namespace fs = std::filesystem;
constexpr int kW = 480, kH = 270;

struct Rgb {
    int w = 0, h = 0;
    std::vector<std::uint8_t> px;
    const std::uint8_t* at(int x, int y) const {
        return &px[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3];
    }
};

Rgb readPng(const fs::path& file) {
    Rgb r;
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) return r;
    r.w = in->spec().width;
    r.h = in->spec().height;
    r.px.resize(std::size_t(r.w) * std::size_t(r.h) * 3);
    in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, r.px.data());
    return r;
}

// The sky colour Session::drawFrame clears to.
bool isSky(const std::uint8_t* p) {
    return std::abs(p[0] - 158) <= 2 && std::abs(p[1] - 181) <= 2 && std::abs(p[2] - 204) <= 2;
}

class BriefingExportTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists("data/generated/rainier.gpkg"))
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA",
                               "demo store missing: run tools/prepare-demo.sh");
        mDir = fs::temp_directory_path() / ("kiosk-briefing-" + std::to_string(::getpid()));
        fs::create_directories(mDir);
        writeBriefing("brief.json", "Chapter two caption\nand its second line");
        writeBriefing("uncaptioned.json", "");
    }
    /** Chapter 1: the overview at +1 h, pausing; chapter 2: the summit at +3 h with the
     *  elevation tint hidden and `caption`. */
    void writeBriefing(const std::string& name, const std::string& caption) const {
        nlohmann::json two = {{"title", "Summit without tint"},
                              {"time", "+3h"},
                              {"viewpoint", "summit"},
                              {"duration", 1},
                              {"layers", {{"relief", {{"enabled", false}}}}}};
        if (!caption.empty()) two["caption"] = caption;
        std::ofstream(mDir / name)
            << nlohmann::json{{"version", 1},
                              {"include", {fs::absolute("scenarios/demo/rainier.json").string()}},
                              {"briefing",
                               {{"chapters",
                                 {{{"title", "Overview first"},
                                   {"time", "+1h"},
                                   {"viewpoint", "overview"},
                                   {"duration", 1},
                                   {"pause", true}},
                                  two}}}}};
    }
    void TearDown() override {
        std::error_code ec;
        if (!mDir.empty()) fs::remove_all(mDir, ec);
    }
    int render(const std::string& scenario, const std::string& args) const {
        const std::string cmd = std::string(KIOSK_GEOKIOSK_BIN) + " render '" + scenario +
                                "' --quiet --size " + std::to_string(kW) + "x" +
                                std::to_string(kH) + " " + args;
        return std::system(cmd.c_str());
    }
    fs::path mDir;
};

TEST_F(BriefingExportTest, ChapterTwoHasItsViewpointLayersAndCaption) {
    // 2 fps: chapter 1 = 2 frames + 2 s (4 frames) holding its end; chapter 2 = 2 frames.
    ASSERT_EQ(
        render((mDir / "brief.json").string(), "--fps 2 --out '" + (mDir / "f/").string() + "'"),
        0);
    ASSERT_TRUE(fs::exists(mDir / "f" / "000008.png"));
    ASSERT_FALSE(fs::exists(mDir / "f" / "000009.png"));
    ASSERT_EQ(render("scenarios/demo/rainier.json",
                     "--time +3h --viewpoint summit --out '" + (mDir / "ref.png").string() + "'"),
              0);
    const Rgb first = readPng(mDir / "f" / "000002.png"), held = readPng(mDir / "f" / "000006.png");
    const Rgb two = readPng(mDir / "f" / "000008.png"), ref = readPng(mDir / "ref.png");
    ASSERT_EQ(two.w, kW);
    ASSERT_EQ(ref.w, kW);
    EXPECT_EQ(first.px, held.px) << "a pausing chapter holds its last frame";

    // Viewpoint: above the caption, the sky is exactly where the summit view has it (and not
    // where chapter 1's overview has it).
    int skyMismatch = 0, skyVsOverview = 0, terrain = 0, terrainChanged = 0;
    for (int y = 0; y < kH * 6 / 10; ++y)
        for (int x = 0; x < kW; ++x) {
            skyMismatch += isSky(ref.at(x, y)) != isSky(two.at(x, y));
            skyVsOverview += isSky(first.at(x, y)) != isSky(two.at(x, y));
            // Layer override: the elevation tint is hidden, so terrain in the middle changes.
            if (x > kW / 4 && x < kW * 3 / 4 && y > kH / 4 && !isSky(ref.at(x, y))) {
                ++terrain;
                const auto *p = ref.at(x, y), *q = two.at(x, y);
                terrainChanged += p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
            }
        }
    EXPECT_EQ(skyMismatch, 0);
    EXPECT_GT(skyVsOverview, 1000);
    ASSERT_GT(terrain, 1000);
    EXPECT_GT(terrainChanged, terrain * 9 / 10);

    // Caption: what the caption adds to the same chapter is one panel, centred, clear of the
    // bottom 5 % (the title-safe area).
    ASSERT_EQ(render((mDir / "uncaptioned.json").string(),
                     "--fps 2 --out '" + (mDir / "u/").string() + "'"),
              0);
    const Rgb bare = readPng(mDir / "u" / "000008.png");
    ASSERT_EQ(bare.w, kW);
    int x0 = kW, x1 = -1, y0 = kH, y1 = -1, n = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const auto *p = bare.at(x, y), *q = two.at(x, y);
            if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
            ++n;
            x0 = std::min(x0, x);
            x1 = std::max(x1, x);
            y0 = std::min(y0, y);
            y1 = std::max(y1, y);
        }
    ASSERT_GT(n, 2000);
    EXPECT_NEAR((x0 + x1) / 2.0, kW / 2.0, 2.0);
    EXPECT_GT(y0, kH / 3);
    EXPECT_LT(y1, kH - kH * 5 / 100);
}

TEST_F(BriefingExportTest, Mp4CarriesTheChaptersAsMarkers) {
    const fs::path mp4 = mDir / "brief.mp4";
    ASSERT_EQ(render((mDir / "brief.json").string(), "--fps 2 --out '" + mp4.string() + "'"), 0);
    const std::string cmd = "ffprobe -v error -show_chapters -of json '" + mp4.string() + "'";
    FILE* p = popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string out;
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    ASSERT_EQ(pclose(p), 0) << "ffprobe (Debian package ffmpeg) is needed: " << out;
    const auto j = nlohmann::json::parse(out, nullptr, false);
    ASSERT_TRUE(j.contains("chapters")) << out;
    const auto& ch = j["chapters"];
    ASSERT_EQ(ch.size(), 2u) << out;
    EXPECT_EQ(ch[0]["tags"]["title"], "Overview first");
    EXPECT_EQ(ch[1]["tags"]["title"], "Summit without tint");
    // 6 frames at 2 fps for chapter 1 (1 s + the 2 s pause hold), then 2 frames.
    EXPECT_NEAR(std::stod(ch[0]["start_time"].get<std::string>()), 0.0, 1e-3);
    EXPECT_NEAR(std::stod(ch[0]["end_time"].get<std::string>()), 3.0, 1e-3);
    EXPECT_NEAR(std::stod(ch[1]["start_time"].get<std::string>()), 3.0, 1e-3);
    EXPECT_NEAR(std::stod(ch[1]["end_time"].get<std::string>()), 4.0, 1e-3);
}

}  // namespace
}  // namespace kiosk
