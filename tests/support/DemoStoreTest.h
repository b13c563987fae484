#pragma once
// GL tests that play the shipped demo: a context as EglTest gives, and the demo store that
// tools/prepare-demo.sh builds (skipped with that hint, or failed under KIOSK_REQUIRE_DATA).
#include "tests/support/EglTestContext.h"

#include <filesystem>

namespace kiosk::test {

class DemoStoreTest : public EglTest {
protected:
    void SetUp() override {
        EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        if (!std::filesystem::exists("data/generated/rainier.gpkg"))
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA",
                               "demo store missing: run tools/prepare-demo.sh");
    }
};

}  // namespace kiosk::test
