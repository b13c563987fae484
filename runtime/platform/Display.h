#pragma once

#include <memory>
#include <string>

#include "runtime/core/Result.h"

namespace kiosk::platform {

enum class DisplayKind { Auto, Kms, X11, Wayland, Headless };

/** @brief Parse `auto|kms|x11|wayland|headless`. */
std::optional<DisplayKind> parseDisplayKind(const std::string& name);
const char* displayKindName(DisplayKind kind) noexcept;

struct DisplayOptions {
    DisplayKind kind = DisplayKind::Auto;
    int width = 0;   ///< 0: the output's native mode (KMS) or the screen size (X11 fullscreen)
    int height = 0;
    bool windowed = false;   ///< X11/Wayland: a normal window instead of fullscreen
    bool vsync = true;       ///< swap interval 1 on displays
    std::string drmDevice;   ///< KMS: /dev/dri/cardN; empty picks the first that has a connector
    std::string connector;   ///< KMS: connector name ("HDMI-A-1") or index; empty: first connected
    /**
     * @brief Asked while a swap waits for the compositor (Wayland frame callbacks): true ends
     * the wait (SIGTERM), so a compositor that stops repainting cannot keep the process alive.
     */
    bool (*shouldStop)() = nullptr;
};

/**
 * @brief What the user asked for through the window system since the last poll. Navigation
 * requests accumulate until the consumer reads them and calls clearRequests().
 */
struct InputState {
    bool quitRequested = false;  ///< window closed, Escape or q pressed
    bool resized = false;
    int orbit = 0;      ///< Left/Right arrows: -1 / +1 per press (heading)
    int tilt = 0;       ///< Up/Down arrows: +1 / -1 per press (pitch)
    int zoom = 0;       ///< +/-: +1 zooms in, -1 out
    int step = 0;       ///< . / , : next / previous key frame
    bool togglePause = false;  ///< space
    bool home = false;         ///< h / Home: back to the scenario's camera
    // The comparison lens (app/LensControl.h): w/a/s/d move, [ / ] size, r turns, c toggles.
    int lensX = 0;     ///< d: +1 (east), a: -1
    int lensY = 0;     ///< w: +1 (north), s: -1
    int lensSize = 0;  ///< ]: +1 larger, [: -1 smaller
    int lensTurn = 0;  ///< r: +1 (15 degrees counter-clockwise)
    bool lensToggle = false;  ///< c
    void clearRequests() {
        orbit = tilt = zoom = step = lensX = lensY = lensSize = lensTurn = 0;
        togglePause = home = lensToggle = false;
    }
};

/**
 * @brief An EGL display with a current OpenGL ES 3 context, and (except headless) a surface that
 * is presented by swapBuffers().
 *
 * Render thread only: the context is current on the thread that created it and every method
 * must be called there. The destructor tears down in reverse order (unbind, surface, context,
 * eglTerminate, eglReleaseThread) and releases the output (KMS: restores the previous CRTC).
 */
class Display {
public:
    virtual ~Display() = default;
    Display(const Display&) = delete;
    Display& operator=(const Display&) = delete;

    virtual DisplayKind kind() const noexcept = 0;
    virtual int width() const noexcept = 0;
    virtual int height() const noexcept = 0;
    /** @brief False for headless: the caller renders into its own framebuffer object. */
    virtual bool hasSurface() const noexcept { return true; }
    /** @brief Present the back buffer (page flip on KMS). False when presentation failed. */
    virtual bool swapBuffers() = 0;
    virtual void pollInput(InputState& state) { (void)state; }
    /** @brief `GL_RENDERER`-like description for logs, e.g. "x11 1920x1080 (EGL 1.5)". */
    virtual std::string describe() const = 0;

protected:
    Display() = default;
};

/**
 * @brief Create the display the options ask for. `Auto` picks KMS when no desktop session exists
 * and a DRM device does, X11 when DISPLAY is set, Wayland when WAYLAND_DISPLAY is set (and the
 * backend is built); otherwise fails. Failure diagnostics carry code PLATFORM_* and exactly one
 * line of text; callers exit with kExitCannotRun.
 */
Result<std::unique_ptr<Display>> createDisplay(const DisplayOptions& options);

/** @brief Which backends were compiled in (CMake options KIOSK_PLATFORM_*). */
bool backendAvailable(DisplayKind kind) noexcept;

}  // namespace kiosk::platform
