// Video export (issue 18) through the geokiosk binary: 3 s of the demo rendered to PNGs and to
// video; the lossless MKV decodes to the PNG pixels exactly, the default H.264 stays above
// 40 dB PSNR against them and says BT.709 limited range, the VP9 WebM plays back the same
// frames. Videos are decoded with libavcodec in the test (tests/support/VideoDecode).
#include "tests/support/EglTestContext.h"
#include "tests/support/VideoDecode.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

extern "C" {
#include <libavutil/pixfmt.h>
}

namespace kiosk {
namespace {

namespace fs = std::filesystem;
// Small enough to run in seconds; the overlays' text still covers a realistic share of it.
constexpr int kW = 480, kH = 270;
// 3 s of video at the demo's 1200x clock: 31 frames.
const std::string kRange = " --from +0 --to +1h --fps 10";

std::vector<std::uint8_t> readPngRgb(const fs::path& file) {
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) return {};
    std::vector<std::uint8_t> rgb(std::size_t(in->spec().width) * std::size_t(in->spec().height) *
                                  3);
    in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data());
    return rgb;
}

class VideoExportTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists("data/generated/rainier.gpkg"))
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA",
                               "demo store missing: run tools/prepare-demo.sh");
        mDir = fs::temp_directory_path() / ("kiosk-export-" + std::to_string(::getpid()));
        fs::create_directories(mDir);
    }
    void TearDown() override {
        std::error_code ec;
        if (!mDir.empty()) fs::remove_all(mDir, ec);
    }

    int render(const std::string& out, const std::string& extra = kRange) const {
        const std::string cmd = std::string(KIOSK_GEOKIOSK_BIN) +
                                " render scenarios/demo/rainier.json --quiet --size " +
                                std::to_string(kW) + "x" + std::to_string(kH) + extra + " --out '" +
                                (mDir / out).string() + "'";
        return std::system(cmd.c_str());
    }
    std::vector<std::vector<std::uint8_t>> pngs(const std::string& folder) const {
        std::vector<std::vector<std::uint8_t>> out;
        for (int i = 1;; ++i) {
            char name[32];
            std::snprintf(name, sizeof name, "%06d.png", i);
            if (!fs::exists(mDir / folder / name)) break;
            out.push_back(readPngRgb(mDir / folder / name));
        }
        return out;
    }

    fs::path mDir;
};

// One test, one set of PNGs: the same 31 frames against each format.
TEST_F(VideoExportTest, ThreeSecondsOfTheDemoInEveryFormatMatchThePngs) {
    ASSERT_EQ(render("png/"), 0);
    const auto ref = pngs("png");
    ASSERT_EQ(ref.size(), 31u);

    ASSERT_EQ(render("demo.mkv"), 0);
    const auto mkv = test::decodeVideo(mDir / "demo.mkv");
    ASSERT_TRUE(mkv.error.empty()) << mkv.error;
    EXPECT_EQ(mkv.codec, "ffv1");
    EXPECT_EQ(mkv.width, kW);
    EXPECT_EQ(mkv.height, kH);
    EXPECT_NEAR(mkv.fps, 10.0, 1e-6);
    EXPECT_EQ(mkv.colorSpace, AVCOL_SPC_RGB);
    ASSERT_EQ(mkv.frames.size(), ref.size());
    for (std::size_t f = 0; f < ref.size(); ++f) {
        ASSERT_EQ(mkv.frames[f].size(), ref[f].size());
        std::size_t differing = 0;
        for (std::size_t i = 0; i < ref[f].size(); ++i) differing += mkv.frames[f][i] != ref[f][i];
        EXPECT_EQ(differing, 0u) << "lossless frame " << f + 1 << " differs from its PNG";
    }

    ASSERT_EQ(render("demo.mp4"), 0);
    const auto mp4 = test::decodeVideo(mDir / "demo.mp4");
    ASSERT_TRUE(mp4.error.empty()) << mp4.error;
    EXPECT_EQ(mp4.codec, "h264");
    EXPECT_EQ(mp4.colorPrimaries, AVCOL_PRI_BT709);
    EXPECT_EQ(mp4.colorTrc, AVCOL_TRC_BT709);
    EXPECT_EQ(mp4.colorSpace, AVCOL_SPC_BT709);
    EXPECT_EQ(mp4.colorRange, AVCOL_RANGE_MPEG);
    ASSERT_EQ(mp4.frames.size(), ref.size());
    EXPECT_GT(test::clipPsnr(ref, mp4.frames), 40.0);

    ASSERT_EQ(render("demo.webm"), 0);
    const auto webm = test::decodeVideo(mDir / "demo.webm");
    ASSERT_TRUE(webm.error.empty()) << webm.error;
    EXPECT_EQ(webm.codec.substr(0, 3), "vp9");
    EXPECT_EQ(webm.colorSpace, AVCOL_SPC_BT709);
    ASSERT_EQ(webm.frames.size(), ref.size());
    EXPECT_GT(test::clipPsnr(ref, webm.frames), 35.0);
}

TEST_F(VideoExportTest, CrfSetsTheQuality) {
    ASSERT_EQ(render("one.png", " --time +2h"), 0);
    const std::vector<std::vector<std::uint8_t>> ref{readPngRgb(mDir / "one.png")};
    ASSERT_EQ(render("fine.mp4", " --time +2h --crf 10"), 0);
    ASSERT_EQ(render("coarse.mp4", " --time +2h --crf 40"), 0);
    const double fine = test::clipPsnr(ref, test::decodeVideo(mDir / "fine.mp4").frames);
    const double coarse = test::clipPsnr(ref, test::decodeVideo(mDir / "coarse.mp4").frames);
    EXPECT_GT(fine, coarse + 5.0);
    EXPECT_LT(fs::file_size(mDir / "coarse.mp4"), fs::file_size(mDir / "fine.mp4"));
}

// --preset reaches libx264: at the same CRF a slower preset finds a smaller file (ultrafast has
// no CABAC and no B-frames), and both keep the quality the CRF asks for.
TEST_F(VideoExportTest, PresetTradesEncodingTimeForFileSize) {
    const std::string range = " --from +2h --to +2h20m --fps 10";  // 11 frames
    ASSERT_EQ(render("ref/", range), 0);
    const auto ref = pngs("ref");
    ASSERT_EQ(ref.size(), 11u);
    ASSERT_EQ(render("fast.mp4", range + " --preset ultrafast --crf 18"), 0);
    ASSERT_EQ(render("small.mp4", range + " --preset veryfast --crf 18"), 0);
    EXPECT_LT(fs::file_size(mDir / "small.mp4") * 5 / 4, fs::file_size(mDir / "fast.mp4"));
    const double fast = test::clipPsnr(ref, test::decodeVideo(mDir / "fast.mp4").frames);
    const double small = test::clipPsnr(ref, test::decodeVideo(mDir / "small.mp4").frames);
    std::printf("PSNR ultrafast %.2f dB (%ju bytes), veryfast %.2f dB (%ju bytes)\n", fast,
                std::uintmax_t(fs::file_size(mDir / "fast.mp4")), small,
                std::uintmax_t(fs::file_size(mDir / "small.mp4")));
    EXPECT_GT(fast, 36.0);
    EXPECT_GT(small, 36.0);
}

}  // namespace
}  // namespace kiosk
