#include "runtime/core/Progress.h"

#include <gtest/gtest.h>

namespace kiosk {

TEST(Progress, EtaFromTheRateSoFar) {
    EXPECT_EQ(Progress::eta(0.0, 0, 100), "?");      // nothing done: no rate yet
    EXPECT_EQ(Progress::eta(10.0, 50, 100), "10s");  // half in 10 s: 10 s left
    EXPECT_EQ(Progress::eta(30.0, 10, 100), "4m30s");
    EXPECT_EQ(Progress::eta(100.0, 1, 100), "2h45m");
    EXPECT_EQ(Progress::eta(5.0, 100, 100), "0s");
}

}  // namespace kiosk
