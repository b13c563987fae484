#include "runtime/export/Yuv420.h"

#include <cstddef>

namespace kiosk::video {
namespace {

// BT.709 luma weights; limited range scales luma to 219/255 and chroma to 224/255 of full scale.
constexpr double kKr = 0.2126, kKb = 0.0722, kKg = 1.0 - kKr - kKb;
constexpr double kLumaScale = 219.0 / 255.0, kChromaScale = 224.0 / 255.0;

constexpr int fixed(double v, int bits) {
    const double s = v * double(1 << bits);
    return int(s < 0 ? s - 0.5 : s + 0.5);
}

// Luma in 16.16 fixed point.
constexpr int kYr = fixed(kKr * kLumaScale, 16), kYg = fixed(kKg * kLumaScale, 16),
              kYb = fixed(kKb * kLumaScale, 16);
// Chroma in 16.16 on the SUM of a 2x2 block (hence 18 bits of shift). The green weight takes the
// rounding residue so that every grey maps to exactly 128.
constexpr int kUr = fixed(-kKr / (2 * (1 - kKb)) * kChromaScale, 16),
              kUb = fixed(0.5 * kChromaScale, 16), kUg = -kUr - kUb;
constexpr int kVr = fixed(0.5 * kChromaScale, 16),
              kVb = fixed(-kKb / (2 * (1 - kKr)) * kChromaScale, 16), kVg = -kVr - kVb;
static_assert(kYr + kYg + kYb == fixed(kLumaScale, 16), "white must map to 235");

constexpr int kYOffset = (16 << 16) + (1 << 15);
constexpr int kCOffset = (128 << 18) + (1 << 17);

inline std::uint8_t luma(const std::uint8_t* p) {
    return std::uint8_t((kYr * p[0] + kYg * p[1] + kYb * p[2] + kYOffset) >> 16);
}

}  // namespace

// Compiled with -O3 (runtime/export/CMakeLists.txt): the row loops then vectorise.
void rgbaToYuv420Bt709(const std::uint8_t* rgba, int width, int height, const Yuv420Planes& out) {
    const std::size_t row = std::size_t(width) * 4;
    for (int y = 0; y < height; y += 2) {
        // Output rows y and y+1 are source rows height-1-y and height-2-y (bottom row first).
        const std::uint8_t* s0 = rgba + std::size_t(height - 1 - y) * row;
        const std::uint8_t* s1 = s0 - row;
        std::uint8_t* y0 = out.y + std::ptrdiff_t(y) * out.yStride;
        std::uint8_t* y1 = y0 + out.yStride;
        std::uint8_t* u = out.u + std::ptrdiff_t(y / 2) * out.uStride;
        std::uint8_t* v = out.v + std::ptrdiff_t(y / 2) * out.vStride;
        for (int x = 0; x < width; ++x) {
            y0[x] = luma(s0 + 4 * x);
            y1[x] = luma(s1 + 4 * x);
        }
        for (int x = 0; x < width / 2; ++x) {
            const std::uint8_t* a = s0 + 8 * x;
            const std::uint8_t* b = s1 + 8 * x;
            const int r = a[0] + a[4] + b[0] + b[4];
            const int g = a[1] + a[5] + b[1] + b[5];
            const int bl = a[2] + a[6] + b[2] + b[6];
            u[x] = std::uint8_t((kUr * r + kUg * g + kUb * bl + kCOffset) >> 18);
            v[x] = std::uint8_t((kVr * r + kVg * g + kVb * bl + kCOffset) >> 18);
        }
    }
}

}  // namespace kiosk::video
