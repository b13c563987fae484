// Rendered frames as PNG (io::encodeFramePng): two stripes deflated on two threads and joined
// into one zlib stream; libspng (another decoder) must read back exactly the frame's RGB.
#include "runtime/io/FramePng.h"
#include "runtime/io/ImageCodec.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace kiosk::io {
namespace {

void expectRoundTrip(int width, int height, bool noise) {
    SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height));
    std::mt19937 rng(std::uint32_t(width * 7919 + height));
    std::vector<std::uint8_t> rgba(std::size_t(width) * std::size_t(height) * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i)
        rgba[i] = noise ? std::uint8_t(rng()) : std::uint8_t((i / 4 % 97) * (i % 4 + 1));
    auto png = encodeFramePng(rgba.data(), width, height);
    ASSERT_TRUE(png.ok()) << png.diagnostics.format();
    auto again = encodeFramePng(rgba.data(), width, height);
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(*png.value, *again.value) << "the bytes depend only on the pixels";
    auto back = decodeRgba8(png->data(), png->size(), "frame");
    ASSERT_TRUE(back.ok()) << back.diagnostics.format();
    ASSERT_EQ(back->width, width);
    ASSERT_EQ(back->height, height);
    ASSERT_EQ(back->samples8.size(), rgba.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < rgba.size(); ++i)
        differing += back->samples8[i] != (i % 4 == 3 ? 255 : rgba[i]) ? 1u : 0u;
    EXPECT_EQ(differing, 0u) << "RGB as rendered, alpha dropped";
}

TEST(FramePng, EveryPixelReadsBackFromOneZlibStreamOfTwoStripes) {
    expectRoundTrip(1, 1, true);  // one row: the first stripe is empty
    expectRoundTrip(5, 2, true);
    expectRoundTrip(33, 17, false);
    // Rows longer than deflate's 32 KiB window, and a dictionary of several rows.
    expectRoundTrip(12000, 9, true);
    expectRoundTrip(1920, 1080, false);
}

TEST(FramePng, EmptyFramesAreRefused) {
    const std::uint8_t px[4] = {1, 2, 3, 4};
    for (auto [w, h] : {std::pair{0, 1}, std::pair{1, 0}, std::pair{-1, 5}}) {
        auto png = encodeFramePng(px, w, h);
        ASSERT_FALSE(png.ok());
        EXPECT_TRUE(png.diagnostics.has("IMAGE_ENCODE"));
    }
}

}  // namespace
}  // namespace kiosk::io
