// X11 backend under a private Xvfb: window creation, fullscreen without a WM, presentation
// (checked from a second X connection with XGetImage), input and resize events.
#include "runtime/gl/Context.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/platform/Display.h"
#include "tests/platform/XvfbServer.h"
#include "tests/support/EglTestContext.h"

#include <GLES3/gl3.h>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <thread>

// Xlib last: its macros (None, Bool, Status) must not reach the headers above.
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>

namespace kiosk::platform {
namespace {

using Rgba = std::array<std::uint8_t, 4>;

/** @brief A second X connection, playing the part of the user and of the screen. */
class Observer {
public:
    explicit Observer(const std::string& display) : mDpy(XOpenDisplay(display.c_str())) {}
    ~Observer() {
        if (mDpy) XCloseDisplay(mDpy);
    }
    Observer(const Observer&) = delete;
    Observer& operator=(const Observer&) = delete;
    bool ok() const { return mDpy != nullptr; }

    /** @brief The top-level window our backend created (WM_NAME "geokiosk"). */
    Window findKioskWindow() {
        Window root = DefaultRootWindow(mDpy), parent = 0, *children = nullptr;
        unsigned n = 0;
        Window found = 0;
        if (!XQueryTree(mDpy, root, &root, &parent, &children, &n)) return 0;
        for (unsigned i = 0; i < n && !found; ++i) {
            char* name = nullptr;
            if (XFetchName(mDpy, children[i], &name) && name) {
                if (std::strcmp(name, "geokiosk") == 0) found = children[i];
                XFree(name);
            }
        }
        if (children) XFree(children);
        return found;
    }

    /** @brief Pixel of the root window (what is on screen), as RGBA with A = 255. */
    Rgba screenPixel(int x, int y) {
        XSync(mDpy, False);
        XImage* img = XGetImage(mDpy, DefaultRootWindow(mDpy), x, y, 1, 1, AllPlanes, ZPixmap);
        if (!img) return {0, 0, 0, 0};
        const unsigned long p = XGetPixel(img, 0, 0);
        const auto channel = [p](unsigned long mask) {
            int shift = 0;
            while (mask && !(mask & 1ul)) {
                mask >>= 1;
                ++shift;
            }
            return std::uint8_t((p >> shift) & 0xff);
        };
        Rgba out = {channel(img->red_mask), channel(img->green_mask), channel(img->blue_mask), 255};
        XDestroyImage(img);
        return out;
    }

    /** @brief Poll the screen until (x,y) shows `want` (presentation is asynchronous). */
    Rgba waitForPixel(int x, int y, const Rgba& want) {
        Rgba got{};
        for (int i = 0; i < 100; ++i) {
            got = screenPixel(x, y);
            if (got == want) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return got;
    }

    void sendDeleteWindow(Window w) {
        XEvent ev{};
        ev.xclient.type = ClientMessage;
        ev.xclient.window = w;
        ev.xclient.message_type = XInternAtom(mDpy, "WM_PROTOCOLS", False);
        ev.xclient.format = 32;
        ev.xclient.data.l[0] = long(XInternAtom(mDpy, "WM_DELETE_WINDOW", False));
        ev.xclient.data.l[1] = CurrentTime;
        XSendEvent(mDpy, w, False, NoEventMask, &ev);
        XSync(mDpy, False);
    }

    void sendKey(Window w, KeySym sym) {
        XEvent ev{};
        ev.xkey.type = KeyPress;
        ev.xkey.display = mDpy;
        ev.xkey.window = w;
        ev.xkey.root = DefaultRootWindow(mDpy);
        ev.xkey.keycode = XKeysymToKeycode(mDpy, sym);
        ev.xkey.same_screen = True;
        XSendEvent(mDpy, w, True, KeyPressMask, &ev);
        XSync(mDpy, False);
    }

    void resize(Window w, unsigned width, unsigned height) {
        XResizeWindow(mDpy, w, width, height);
        XSync(mDpy, False);
    }

private:
    ::Display* mDpy;
};

class X11DisplayTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!backendAvailable(DisplayKind::X11)) GTEST_SKIP() << "built without KIOSK_PLATFORM_X11";
        if (test::XvfbServer::binary().empty())
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_GL", "Xvfb is not installed (apt-get install xvfb)");
        std::string error;
        ASSERT_TRUE(mServer.start(640, 480, error)) << error;
        if (const char* old = std::getenv("DISPLAY")) mOldDisplay = old;
        setenv("DISPLAY", mServer.display().c_str(), 1);
    }
    void TearDown() override {
        if (mOldDisplay)
            setenv("DISPLAY", mOldDisplay->c_str(), 1);
        else
            unsetenv("DISPLAY");
    }

    std::unique_ptr<Display> create(bool windowed, int width, int height) {
        DisplayOptions opts;
        opts.kind = DisplayKind::X11;
        opts.windowed = windowed;
        opts.width = width;
        opts.height = height;
        opts.vsync = false;
        auto display = createDisplay(opts);
        EXPECT_TRUE(display.ok()) << display.diagnostics.format();
        if (!display) return nullptr;
        auto caps = gl::initContext();
        EXPECT_TRUE(caps.ok()) << caps.diagnostics.format();
        return std::move(*display.value);
    }

    /** @brief A windowed kiosk and a second X client (the user) that has found its window. */
    struct UserWindow {
        std::unique_ptr<Display> display;
        std::unique_ptr<Observer> user;
        Window window = 0;
    };
    UserWindow openWithUser(int width, int height) {
        UserWindow u;
        u.display = create(true, width, height);
        if (!u.display) return u;
        u.user = std::make_unique<Observer>(mServer.display());
        EXPECT_TRUE(u.user->ok());
        if (u.user->ok()) u.window = u.user->findKioskWindow();
        return u;
    }

    /** @brief Poll the display's input every 10 ms, at most `tries` times, until `done(input)`. */
    template <class Done>
    static void pollUntil(Display& display, InputState& input, int tries, Done done) {
        for (int i = 0; i < tries && !done(input); ++i) {
            display.pollInput(input);
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    }

    /** @brief Clear the window's back buffer, read it back with glReadPixels, check all of it. */
    void clearAndCheckBackBuffer(const Display& display, const Rgba& c) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, display.width(), display.height());
        glClearColor(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, c[3] / 255.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl::Image img = gl::readPixels(display.width(), display.height());
        EXPECT_GL_OK();
        int wrong = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                if (!std::equal(c.begin(), c.begin() + 3, img.pixel(x, y))) ++wrong;
        EXPECT_EQ(wrong, 0) << "pixels of the back buffer differ from the clear colour";
    }

    test::XvfbServer mServer;
    std::optional<std::string> mOldDisplay;
};

TEST_F(X11DisplayTest, WindowedClearSwapReadBack) {
    auto display = create(true, 320, 240);
    ASSERT_TRUE(display);
    EXPECT_EQ(display->kind(), DisplayKind::X11);
    EXPECT_EQ(display->width(), 320);
    EXPECT_EQ(display->height(), 240);
    EXPECT_TRUE(display->hasSurface());
    EXPECT_NE(display->describe().find("x11 320x240 windowed"), std::string::npos)
        << display->describe();

    Observer screen(mServer.display());
    ASSERT_TRUE(screen.ok());
    ASSERT_NE(screen.findKioskWindow(), Window(0));

    const Rgba first = {51, 102, 204, 255};
    clearAndCheckBackBuffer(*display, first);
    ASSERT_TRUE(display->swapBuffers());
    // No WM: the window sits at the origin; (10,10) is inside it, (400,300) outside.
    EXPECT_EQ(screen.waitForPixel(10, 10, first), first);
    EXPECT_EQ(screen.waitForPixel(319, 239, first), first);
    EXPECT_NE(screen.screenPixel(400, 300), first);

    // A second frame replaces the first on screen.
    const Rgba second = {255, 128, 0, 255};
    clearAndCheckBackBuffer(*display, second);
    ASSERT_TRUE(display->swapBuffers());
    EXPECT_EQ(screen.waitForPixel(160, 120, second), second);

    InputState input;
    display->pollInput(input);
    EXPECT_FALSE(input.quitRequested);
}

TEST_F(X11DisplayTest, FullscreenCoversTheScreen) {
    auto display = create(false, 0, 0);
    ASSERT_TRUE(display);
    EXPECT_EQ(display->width(), 640);
    EXPECT_EQ(display->height(), 480);
    EXPECT_NE(display->describe().find("fullscreen (no WM)"), std::string::npos)
        << display->describe();

    const Rgba c = {17, 34, 68, 255};
    clearAndCheckBackBuffer(*display, c);
    ASSERT_TRUE(display->swapBuffers());
    Observer screen(mServer.display());
    ASSERT_TRUE(screen.ok());
    EXPECT_EQ(screen.waitForPixel(0, 0, c), c);
    EXPECT_EQ(screen.waitForPixel(639, 479, c), c);
    EXPECT_EQ(screen.waitForPixel(320, 240, c), c);
}

TEST_F(X11DisplayTest, FullscreenIgnoresRequestedSize) {
    auto display = create(false, 320, 200);
    ASSERT_TRUE(display);
    EXPECT_EQ(display->width(), 640);
    EXPECT_EQ(display->height(), 480);
}

TEST_F(X11DisplayTest, WindowCloseRequestsQuit) {
    auto [display, user, w] = openWithUser(200, 100);
    ASSERT_NE(w, Window(0));
    user->sendDeleteWindow(w);
    InputState input;
    pollUntil(*display, input, 100, [](const InputState& in) { return in.quitRequested; });
    EXPECT_TRUE(input.quitRequested);
}

TEST_F(X11DisplayTest, EscapeAndQRequestQuitOtherKeysDoNot) {
    auto [display, user, w] = openWithUser(200, 100);
    ASSERT_NE(w, Window(0));

    const auto pump = [&](InputState& input) {
        pollUntil(*display, input, 20, [](const InputState&) { return false; });
    };
    InputState other;
    user->sendKey(w, XK_a);
    pump(other);
    EXPECT_FALSE(other.quitRequested);

    for (KeySym sym : {KeySym(XK_Escape), KeySym(XK_q)}) {
        InputState input;
        user->sendKey(w, sym);
        pump(input);
        EXPECT_TRUE(input.quitRequested) << XKeysymToString(sym);
    }
}

TEST_F(X11DisplayTest, ResizeIsTracked) {
    auto [display, user, w] = openWithUser(320, 240);
    ASSERT_NE(w, Window(0));
    user->resize(w, 400, 300);
    InputState input;
    pollUntil(*display, input, 100, [](const InputState& in) { return in.resized; });
    EXPECT_TRUE(input.resized);
    EXPECT_EQ(display->width(), 400);
    EXPECT_EQ(display->height(), 300);

    // The EGL surface follows on the next frame: the whole new area takes the clear colour.
    const Rgba c = {0, 255, 0, 255};
    ASSERT_TRUE(display->swapBuffers());
    clearAndCheckBackBuffer(*display, c);
    ASSERT_TRUE(display->swapBuffers());
    EXPECT_EQ(user->waitForPixel(399, 299, c), c);
}

TEST_F(X11DisplayTest, LensKeysAccumulateUntilCleared) {
    // The comparison lens keys of `play` (docs/cli.md): w/a/s/d, [ ], r, c.
    auto [display, user, w] = openWithUser(200, 100);
    ASSERT_NE(w, Window(0));
    for (KeySym sym : {XK_d, XK_d, XK_w, XK_s, XK_s, XK_s, XK_a, XK_bracketright, XK_bracketright,
                       XK_bracketleft, XK_r, XK_c})
        user->sendKey(w, sym);
    InputState input;
    pollUntil(*display, input, 50, [](const InputState& in) { return in.lensToggle; });
    EXPECT_EQ(input.lensX, 1);
    EXPECT_EQ(input.lensY, -2);
    EXPECT_EQ(input.lensSize, 1);
    EXPECT_EQ(input.lensTurn, 1);
    EXPECT_TRUE(input.lensToggle);
    EXPECT_FALSE(input.quitRequested);
    input.clearRequests();
    EXPECT_EQ(input.lensX, 0);
    EXPECT_EQ(input.lensSize, 0);
    EXPECT_FALSE(input.lensToggle);
}

}  // namespace
}  // namespace kiosk::platform
