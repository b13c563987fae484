#include "runtime/loader/UploadBudget.h"

#include <gtest/gtest.h>

namespace kiosk::loader {
namespace {

TEST(UploadBudget, BytesLimitPerFrameWithProgressGuarantee) {
    FakeClock clock;
    UploadBudget budget(1000, 4.0, &clock);
    budget.beginFrame();
    EXPECT_TRUE(budget.allow(5000));  // first upload always goes through
    budget.consume(5000);
    EXPECT_FALSE(budget.allow(1));
    EXPECT_EQ(budget.uploads(), 1u);

    budget.beginFrame();
    EXPECT_EQ(budget.bytesUsed(), 0u);
    EXPECT_TRUE(budget.allow(600));
    budget.consume(600);
    EXPECT_TRUE(budget.allow(400));
    EXPECT_FALSE(budget.allow(401));
    budget.consume(400);
    EXPECT_FALSE(budget.allow(1));
    EXPECT_EQ(budget.bytesUsed(), 1000u);
}

TEST(UploadBudget, TimeLimitPerFrame) {
    FakeClock clock(100.0);
    UploadBudget budget(1u << 30, 4.0, &clock);
    budget.beginFrame();
    budget.consume(10);
    clock.advance(0.003);
    EXPECT_NEAR(budget.msUsed(), 3.0, 1e-6);
    EXPECT_TRUE(budget.allow(10));
    clock.advance(0.0015);
    EXPECT_FALSE(budget.allow(10));
    budget.beginFrame();
    EXPECT_TRUE(budget.allow(10));
    budget.setLimits(5, 4.0);
    budget.consume(5);
    EXPECT_FALSE(budget.allow(1));
}

}  // namespace
}  // namespace kiosk::loader
