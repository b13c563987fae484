// The headless backend end to end: createDisplay(Headless) gives a current ES 3 context that
// renders into an offscreen target and reads back exact pixels.
#include "runtime/gl/Context.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/platform/Display.h"
#include "tests/support/EglTestContext.h"

#include <GLES3/gl3.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace kiosk::platform {
namespace {

TEST(SurfacelessDisplay, ClearColourReadsBackExactly) {
    DisplayOptions opts;
    opts.kind = DisplayKind::Headless;
    opts.width = 64;
    opts.height = 32;
    auto display = createDisplay(opts);
    if (!display) KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_GL", display.diagnostics.format());
    auto& d = **display;
    EXPECT_EQ(d.kind(), DisplayKind::Headless);
    EXPECT_FALSE(d.hasSurface());
    EXPECT_EQ(d.width(), 64);
    EXPECT_EQ(d.height(), 32);
    EXPECT_NE(d.describe().find("headless 64x32"), std::string::npos) << d.describe();

    auto caps = gl::initContext();
    ASSERT_TRUE(caps.ok()) << caps.diagnostics.format();
    EXPECT_GE(caps->majorVersion, 3);

    auto rt = gl::RenderTarget::create(d.width(), d.height());
    ASSERT_TRUE(rt.ok()) << rt.diagnostics.format();
    rt->bind();
    glClearColor(10 / 255.0f, 20 / 255.0f, 30 / 255.0f, 40 / 255.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::Image img = rt->readColor();
    EXPECT_GL_OK();
    ASSERT_EQ(img.width, 64);
    ASSERT_EQ(img.height, 32);
    const std::uint8_t want[4] = {10, 20, 30, 40};
    int wrong = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (!std::equal(want, want + 4, img.pixel(x, y))) ++wrong;
    EXPECT_EQ(wrong, 0);
    EXPECT_TRUE(d.swapBuffers());  // a no-op that reports success
}

TEST(SurfacelessDisplay, DefaultSizeIs720p) {
    DisplayOptions opts;
    opts.kind = DisplayKind::Headless;
    auto display = createDisplay(opts);
    if (!display) KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_GL", display.diagnostics.format());
    EXPECT_EQ((*display)->width(), 1280);
    EXPECT_EQ((*display)->height(), 720);
}

TEST(SurfacelessDisplay, TwoDisplaysInSequence) {
    // The destructor must leave EGL reusable (eglTerminate + eglReleaseThread).
    for (int i = 0; i < 2; ++i) {
        DisplayOptions opts;
        opts.kind = DisplayKind::Headless;
        opts.width = 8;
        opts.height = 8;
        auto display = createDisplay(opts);
        if (!display) KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_GL", display.diagnostics.format());
        auto rt = gl::RenderTarget::create(8, 8);
        ASSERT_TRUE(rt.ok()) << rt.diagnostics.format();
        rt->bind();
        glClearColor(1, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        EXPECT_EQ(rt->readColor().pixel(7, 7)[0], 255) << "iteration " << i;
    }
}

}  // namespace
}  // namespace kiosk::platform
