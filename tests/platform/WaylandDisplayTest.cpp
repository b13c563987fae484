// Wayland backend under a private headless Weston: xdg-shell configure (fullscreen size comes
// from the compositor), rendering into the window's back buffer, presentation.
#include "runtime/gl/Context.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/platform/Display.h"
#include "tests/platform/WestonServer.h"
#include "tests/support/EglTestContext.h"

#include <GLES3/gl3.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

namespace kiosk::platform {
namespace {

class WaylandDisplayTest : public ::testing::Test {
protected:
    void start(const std::string& shell) {
        if (!backendAvailable(DisplayKind::Wayland))
            GTEST_SKIP() << "built without KIOSK_PLATFORM_WAYLAND";
        if (test::WestonServer::binary().empty())
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_GL",
                               "weston is not installed (apt-get install weston)");
        std::string error;
        ASSERT_TRUE(mServer.start(640, 480, shell, error)) << error;
        if (const char* old = std::getenv("WAYLAND_DISPLAY")) mOld = old;
        setenv("WAYLAND_DISPLAY", mServer.socketName().c_str(), 1);
    }
    void TearDown() override {
        if (mOld)
            setenv("WAYLAND_DISPLAY", mOld->c_str(), 1);
        else
            unsetenv("WAYLAND_DISPLAY");
    }

    std::unique_ptr<Display> create(bool windowed, int width, int height) {
        DisplayOptions opts;
        opts.kind = DisplayKind::Wayland;
        opts.windowed = windowed;
        opts.width = width;
        opts.height = height;
        auto display = createDisplay(opts);
        EXPECT_TRUE(display.ok()) << display.diagnostics.format();
        if (!display) return nullptr;
        auto caps = gl::initContext();
        EXPECT_TRUE(caps.ok()) << caps.diagnostics.format();
        return std::move(*display.value);
    }

    void clearAndCheck(const Display& display, const std::array<std::uint8_t, 3>& c) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, display.width(), display.height());
        glClearColor(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        const gl::Image img = gl::readPixels(display.width(), display.height());
        EXPECT_GL_OK();
        int wrong = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                if (!std::equal(c.begin(), c.end(), img.pixel(x, y))) ++wrong;
        EXPECT_EQ(wrong, 0);
    }

    test::WestonServer mServer;
    std::optional<std::string> mOld;
};

TEST_F(WaylandDisplayTest, FullscreenTakesTheOutputSize) {
    start("desktop-shell.so");  // weston 10 kiosk-shell never repaints headless
    if (IsSkipped() || HasFatalFailure()) return;
    auto display = create(false, 0, 0);
    ASSERT_TRUE(display);
    EXPECT_EQ(display->kind(), DisplayKind::Wayland);
    EXPECT_EQ(display->width(), 640);
    EXPECT_EQ(display->height(), 480);
    EXPECT_NE(display->describe().find("wayland 640x480 fullscreen"), std::string::npos)
        << display->describe();
    clearAndCheck(*display, {12, 34, 56});
    EXPECT_TRUE(display->swapBuffers());
    clearAndCheck(*display, {200, 100, 50});
    EXPECT_TRUE(display->swapBuffers());  // waits for the compositor's frame callback
    InputState input;
    display->pollInput(input);
    EXPECT_FALSE(input.quitRequested);
}

TEST_F(WaylandDisplayTest, WindowedKeepsTheRequestedSize) {
    start("desktop-shell.so");
    if (IsSkipped() || HasFatalFailure()) return;
    auto display = create(true, 320, 240);
    ASSERT_TRUE(display);
    EXPECT_EQ(display->width(), 320);
    EXPECT_EQ(display->height(), 240);
    clearAndCheck(*display, {0, 255, 0});
    EXPECT_TRUE(display->swapBuffers());
}

}  // namespace
}  // namespace kiosk::platform
