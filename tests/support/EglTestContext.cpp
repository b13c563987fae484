#include "tests/support/EglTestContext.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace kiosk::test {

bool envFlag(const char* name) {
    const char* v = std::getenv(name);
    return v && std::strcmp(v, "1") == 0;
}

bool glRequired() { return envFlag("KIOSK_REQUIRE_GL"); }

void EglTest::SetUp() {
    platform::DisplayOptions opts;
    opts.kind = platform::DisplayKind::Headless;
    auto display = platform::createDisplay(opts);
    if (!display) {
        std::string why = "no surfaceless EGL/GLES3 context: " + display.diagnostics.format();
        if (glRequired()) FAIL() << why << " (KIOSK_REQUIRE_GL=1)";
        GTEST_SKIP() << why;
    }
    mDisplay = std::move(*display.value);
    auto caps = gl::initContext();
    ASSERT_TRUE(caps.ok()) << caps.diagnostics.format();
    mCaps = *caps;
}

void EglTest::TearDown() { mDisplay.reset(); }

gl::RenderTarget EglTest::makeTarget(int width, int height) {
    auto rt = gl::RenderTarget::create(width, height);
    EXPECT_TRUE(rt.ok()) << rt.diagnostics.format();
    rt->bind();
    return std::move(*rt.value);
}

std::string sharedData(const std::string& rel) {
    const char* root = std::getenv("KIOSK_SHARED_DATA");
    std::filesystem::path base = root && *root ? root : "../shared/data";
    std::filesystem::path p = base / rel;
    std::error_code ec;
    return std::filesystem::exists(p, ec) ? p.string() : std::string();
}

}  // namespace kiosk::test
