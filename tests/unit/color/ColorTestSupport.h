#pragma once

#include "runtime/color/TransferFunction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace kiosk::test {

/** @brief ../shared/data/<rel> (KIOSK_SHARED_DATA or relative to the repo root); "" if absent. */
inline std::string colorSharedData(const std::string& rel) {
    const char* env = std::getenv("KIOSK_SHARED_DATA");
    const std::filesystem::path base = env ? env : "../shared/data";
    const auto p = base / rel;
    return std::filesystem::exists(p) ? p.string() : std::string();
}

/** @brief What a GL_LINEAR fetch of the LUT at texture coordinate s returns (clamp to edge). */
inline std::array<double, 4> sampleLinear(const std::vector<std::uint8_t>& lut, double s) {
    const int n = int(lut.size() / 4);
    const double x = s * n - 0.5;
    int i0 = int(std::floor(x));
    const double f = x - i0;
    int i1 = i0 + 1;
    i0 = std::clamp(i0, 0, n - 1);
    i1 = std::clamp(i1, 0, n - 1);
    std::array<double, 4> out{};
    for (int c = 0; c < 4; ++c)
        out[std::size_t(c)] = lut[std::size_t(i0) * 4 + std::size_t(c)] * (1 - f) +
                              lut[std::size_t(i1) * 4 + std::size_t(c)] * f;
    return out;
}

inline std::array<int, 4> dn(const color::Rgba& c) {
    return {color::toByte(c.r), color::toByte(c.g), color::toByte(c.b), color::toByte(c.a)};
}

}  // namespace kiosk::test
