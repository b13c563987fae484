#pragma once
// Hand-computed colours against pixels read back: both sides in 8-bit DN, compared per channel
// within 1 DN (the rounding of an RGBA8 target).

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace kiosk::test {

/** @brief A linear colour as the DN an RGBA8 target stores (clamped, rounded). */
inline glm::ivec3 dn(glm::vec3 c) {
    return glm::ivec3(std::lround(std::clamp(c.r, 0.0f, 1.0f) * 255.0f),
                      std::lround(std::clamp(c.g, 0.0f, 1.0f) * 255.0f),
                      std::lround(std::clamp(c.b, 0.0f, 1.0f) * 255.0f));
}

}  // namespace kiosk::test

/** @brief Each of the three channels of `actual` within 1 DN of `expected`. */
#define EXPECT_DN_NEAR(actual, expected)                                             \
    do {                                                                             \
        auto a_ = (actual);                                                          \
        auto e_ = (expected);                                                        \
        for (int c_ = 0; c_ < 3; ++c_)                                               \
            EXPECT_LE(std::abs(a_[c_] - e_[c_]), 1)                                  \
                << "channel " << c_ << ": got " << a_[c_] << " expected " << e_[c_]; \
    } while (0)
