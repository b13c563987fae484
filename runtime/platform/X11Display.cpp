#include "runtime/core/Log.h"
#include "runtime/platform/Backends.h"
#include "runtime/platform/EglCommon.h"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <poll.h>

// Xlib last: its macros (None, Bool, Status, Success, True, False) must not leak into our headers.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>

namespace kiosk::platform {
namespace {

constexpr const char* kBackend = "x11";
constexpr const char* kTag = "platform::X11";
constexpr int kDefaultWindowWidth = 1280;
constexpr int kDefaultWindowHeight = 720;
constexpr int kMapTimeoutMs = 2000;

// Xlib's default error handler prints and calls exit(1); a BadWindow from a stale event or a WM
// that refuses a property must never end the kiosk, so log and carry on.
int onXError(::Display* dpy, XErrorEvent* event) {
    char text[128] = {};
    XGetErrorText(dpy, event->error_code, text, sizeof(text));
    KIOSK_LOG_WARN(kTag, "X error %s (request %d.%d, resource 0x%lx)", text,
                   int(event->request_code), int(event->minor_code), event->resourceid);
    return 0;
}

std::string displayName() {
    const char* v = std::getenv("DISPLAY");
    return v ? v : "";
}

/** @brief Owns the Xlib connection, window, colormap and cursor; closes them in reverse order. */
struct XResources {
    ::Display* dpy = nullptr;
    Window window = 0;
    Colormap colormap = 0;
    Cursor cursor = 0;

    XResources() = default;
    XResources(const XResources&) = delete;
    XResources& operator=(const XResources&) = delete;
    ~XResources() {
        if (!dpy) return;
        if (window) XDestroyWindow(dpy, window);
        if (cursor) XFreeCursor(dpy, cursor);
        if (colormap) XFreeColormap(dpy, colormap);
        XCloseDisplay(dpy);
    }
};

class X11Display final : public Display {
public:
    X11Display() = default;
    ~X11Display() override {
        // EGL surface and display reference the X window and connection: they go first.
        mEgl.reset();
    }

    DisplayKind kind() const noexcept override { return DisplayKind::X11; }
    int width() const noexcept override { return mWidth; }
    int height() const noexcept override { return mHeight; }
    bool swapBuffers() override { return mEgl->swap(); }
    void pollInput(InputState& state) override;
    std::string describe() const override {
        return std::string("x11 ") + std::to_string(mWidth) + "x" + std::to_string(mHeight) +
               (mWindowed           ? " windowed"
                : mOverrideRedirect ? " fullscreen (no WM)"
                                    : " fullscreen") +
               " (EGL " + mEgl->version() + ")";
    }

    bool create(const DisplayOptions& options, Diagnostics& diags);

private:
    EGLDisplay openEglDisplay();
    bool windowManagerRunning() const;
    bool createWindow(VisualID visualId, Diagnostics& diags);
    void hideCursor();
    void waitForMap();

    // Declaration order is destruction order reversed: mEgl is reset explicitly before mX closes.
    XResources mX;
    std::unique_ptr<EglContext> mEgl = std::make_unique<EglContext>();
    Atom mWmDeleteWindow = 0;
    int mWidth = 0;
    int mHeight = 0;
    bool mWindowed = false;
    bool mOverrideRedirect = false;
};

EGLDisplay X11Display::openEglDisplay() {
    // EGL 1.5 / EXT_platform_x11 names the platform explicitly, so a GLVND or Mesa build whose
    // default platform is not X11 (e.g. EGL_PLATFORM=surfaceless in the environment) still works.
    if (hasEglExtension(EGL_NO_DISPLAY, "EGL_KHR_platform_x11") ||
        hasEglExtension(EGL_NO_DISPLAY, "EGL_EXT_platform_x11")) {
        auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
            eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (getPlatformDisplay) {
            EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_X11_KHR, mX.dpy, nullptr);
            if (d != EGL_NO_DISPLAY) return d;
        }
    }
    return eglGetDisplay(reinterpret_cast<EGLNativeDisplayType>(mX.dpy));
}

bool X11Display::windowManagerRunning() const {
    // An EWMH window manager advertises itself through _NET_SUPPORTING_WM_CHECK on the root
    // window (Xvfb alone has none): only then does _NET_WM_STATE_FULLSCREEN mean anything.
    Atom check = XInternAtom(mX.dpy, "_NET_SUPPORTING_WM_CHECK", True);
    if (check == 0) return false;
    Atom type = 0;
    int format = 0;
    unsigned long count = 0, after = 0;
    unsigned char* data = nullptr;
    int rc = XGetWindowProperty(mX.dpy, DefaultRootWindow(mX.dpy), check, 0, 1, False, XA_WINDOW,
                                &type, &format, &count, &after, &data);
    bool present = rc == Success && type == XA_WINDOW && count == 1 && data != nullptr;
    if (data) XFree(data);
    return present;
}

bool X11Display::createWindow(VisualID visualId, Diagnostics& diags) {
    const int screen = DefaultScreen(mX.dpy);
    const Window root = RootWindow(mX.dpy, screen);
    XVisualInfo tmpl{};
    tmpl.visualid = visualId;
    tmpl.screen = screen;
    int n = 0;
    XVisualInfo* vi = XGetVisualInfo(mX.dpy, VisualIDMask | VisualScreenMask, &tmpl, &n);
    if (!vi || n < 1) {
        if (vi) XFree(vi);
        diags.error("PLATFORM_X11_VISUAL", "", kBackend,
                    "the X server has no visual 0x" + std::to_string(visualId) +
                        " for the chosen EGL config");
        return false;
    }
    Visual* visual = vi->visual;
    const int depth = vi->depth;
    XFree(vi);

    const bool wm = windowManagerRunning();
    mOverrideRedirect = !mWindowed && !wm;
    mX.colormap = XCreateColormap(mX.dpy, root, visual, AllocNone);
    XSetWindowAttributes attrs{};
    attrs.colormap = mX.colormap;
    attrs.background_pixel = 0;
    attrs.border_pixel = 0;
    attrs.event_mask = StructureNotifyMask | KeyPressMask | ExposureMask;
    attrs.override_redirect = mOverrideRedirect ? True : False;
    const unsigned long mask =
        CWColormap | CWBackPixel | CWBorderPixel | CWEventMask | CWOverrideRedirect;
    mX.window = XCreateWindow(mX.dpy, root, 0, 0, unsigned(mWidth), unsigned(mHeight), 0, depth,
                              InputOutput, visual, mask, &attrs);
    if (!mX.window) {
        diags.error("PLATFORM_X11_WINDOW", "", kBackend, "cannot create an X window");
        return false;
    }

    XStoreName(mX.dpy, mX.window, "geokiosk");
    XClassHint hint{};
    char name[] = "geokiosk";
    hint.res_name = name;
    hint.res_class = name;
    XSetClassHint(mX.dpy, mX.window, &hint);
    mWmDeleteWindow = XInternAtom(mX.dpy, "WM_DELETE_WINDOW", False);
    XSetWMProtocols(mX.dpy, mX.window, &mWmDeleteWindow, 1);

    if (mWindowed) {
        // Ask the WM to keep the requested size (tiling WMs otherwise resize at will).
        XSizeHints* sizeHints = XAllocSizeHints();
        if (sizeHints) {
            sizeHints->flags = PSize | PMinSize;
            sizeHints->width = sizeHints->min_width = mWidth;
            sizeHints->height = sizeHints->min_height = mHeight;
            XSetWMNormalHints(mX.dpy, mX.window, sizeHints);
            XFree(sizeHints);
        }
    } else if (wm) {
        // Initial state before mapping: EWMH WMs map the window straight to fullscreen.
        Atom state = XInternAtom(mX.dpy, "_NET_WM_STATE", False);
        Atom fullscreen = XInternAtom(mX.dpy, "_NET_WM_STATE_FULLSCREEN", False);
        XChangeProperty(mX.dpy, mX.window, state, XA_ATOM, 32, PropModeReplace,
                        reinterpret_cast<unsigned char*>(&fullscreen), 1);
    }
    if (!mWindowed) hideCursor();

    XMapRaised(mX.dpy, mX.window);
    waitForMap();
    if (mOverrideRedirect) {
        // No WM hands out focus: take it so Escape / q reach us.
        XSetInputFocus(mX.dpy, mX.window, RevertToParent, CurrentTime);
    }
    XSync(mX.dpy, False);
    return true;
}

void X11Display::hideCursor() {
    // The classic blank cursor: a 1x1 bitmap with an all-zero mask (XFixes would need another
    // library for the same effect).
    static char zero[1] = {0};
    Pixmap blank = XCreateBitmapFromData(mX.dpy, mX.window, zero, 1, 1);
    if (!blank) return;
    XColor black{};
    mX.cursor = XCreatePixmapCursor(mX.dpy, blank, blank, &black, &black, 0, 0);
    XFreePixmap(mX.dpy, blank);
    if (mX.cursor) XDefineCursor(mX.dpy, mX.window, mX.cursor);
}

void X11Display::waitForMap() {
    // Bounded wait: a WM that never maps us must not hang start-up.
    XFlush(mX.dpy);
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(kMapTimeoutMs);
    XEvent ev;
    while (true) {
        if (XCheckTypedWindowEvent(mX.dpy, mX.window, MapNotify, &ev)) return;
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                        deadline - std::chrono::steady_clock::now())
                        .count();
        if (left <= 0) {
            KIOSK_LOG_WARN(kTag, "window not mapped after %d ms; continuing", kMapTimeoutMs);
            return;
        }
        pollfd pfd{ConnectionNumber(mX.dpy), POLLIN, 0};
        poll(&pfd, 1, int(left));
    }
}

bool X11Display::create(const DisplayOptions& options, Diagnostics& diags) {
    static const bool handlerInstalled = (XSetErrorHandler(onXError), true);
    (void)handlerInstalled;

    mX.dpy = XOpenDisplay(nullptr);
    if (!mX.dpy) {
        const std::string name = displayName();
        diags.error("PLATFORM_X11_OPEN", "", kBackend,
                    name.empty() ? "cannot open an X display: DISPLAY is not set"
                                 : "cannot open X display '" + name + "' (from $DISPLAY)");
        return false;
    }
    const int screen = DefaultScreen(mX.dpy);
    mWindowed = options.windowed;
    if (mWindowed) {
        mWidth = options.width > 0 ? options.width : kDefaultWindowWidth;
        mHeight = options.height > 0 ? options.height : kDefaultWindowHeight;
    } else {
        mWidth = DisplayWidth(mX.dpy, screen);
        mHeight = DisplayHeight(mX.dpy, screen);
    }

    // Prefer the screen's default visual (24-bit on Xvfb and most desktops); EglContext falls
    // back to its first config otherwise, and the window then takes that config's visual.
    const VisualID preferred = XVisualIDFromVisual(DefaultVisual(mX.dpy, screen));
    if (!mEgl->init(openEglDisplay(), EGL_WINDOW_BIT, EGLint(preferred), kBackend, diags))
        return false;
    EGLint visualId = 0;
    eglGetConfigAttrib(mEgl->display(), mEgl->config(), EGL_NATIVE_VISUAL_ID, &visualId);
    if (visualId == 0) visualId = EGLint(preferred);
    if (!createWindow(VisualID(visualId), diags)) return false;
    if (!mEgl->makeWindowCurrent(reinterpret_cast<void*>(mX.window), kBackend, diags)) return false;
    mEgl->setSwapInterval(options.vsync ? 1 : 0);
    KIOSK_LOG_INFO(kTag, "%s", describe().c_str());
    return true;
}

void X11Display::pollInput(InputState& state) {
    while (XPending(mX.dpy) > 0) {
        XEvent ev;
        XNextEvent(mX.dpy, &ev);
        switch (ev.type) {
            case ClientMessage:
                if (Atom(ev.xclient.data.l[0]) == mWmDeleteWindow) state.quitRequested = true;
                break;
            case KeyPress: {
                KeySym sym = XLookupKeysym(&ev.xkey, 0);
                switch (sym) {
                    case XK_Escape:
                    case XK_q: state.quitRequested = true; break;
                    case XK_Left: --state.orbit; break;
                    case XK_Right: ++state.orbit; break;
                    case XK_Up: ++state.tilt; break;
                    case XK_Down: --state.tilt; break;
                    case XK_plus:
                    case XK_equal:
                    case XK_KP_Add: ++state.zoom; break;
                    case XK_minus:
                    case XK_KP_Subtract: --state.zoom; break;
                    case XK_period: ++state.step; break;
                    case XK_comma: --state.step; break;
                    case XK_space: state.togglePause = !state.togglePause; break;
                    case XK_h:
                    case XK_Home: state.home = true; break;
                    case XK_w: ++state.lensY; break;
                    case XK_s: --state.lensY; break;
                    case XK_d: ++state.lensX; break;
                    case XK_a: --state.lensX; break;
                    case XK_bracketright: ++state.lensSize; break;
                    case XK_bracketleft: --state.lensSize; break;
                    case XK_r: ++state.lensTurn; break;
                    case XK_c: state.lensToggle = !state.lensToggle; break;
                    default: break;
                }
                break;
            }
            case ConfigureNotify:
                if (ev.xconfigure.window == mX.window &&
                    (ev.xconfigure.width != mWidth || ev.xconfigure.height != mHeight)) {
                    // Mesa resizes the EGL window surface on the next frame by itself.
                    mWidth = ev.xconfigure.width;
                    mHeight = ev.xconfigure.height;
                    state.resized = true;
                }
                break;
            case DestroyNotify:
                if (ev.xdestroywindow.window == mX.window) state.quitRequested = true;
                break;
            default:
                break;
        }
    }
}

}  // namespace

Result<std::unique_ptr<Display>> createX11Display(const DisplayOptions& options) {
    Diagnostics diags;
    auto display = std::make_unique<X11Display>();
    if (!display->create(options, diags)) return diags;
    return std::unique_ptr<Display>(std::move(display));
}

}  // namespace kiosk::platform
