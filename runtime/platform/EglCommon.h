#pragma once

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

#include "runtime/core/Diagnostics.h"

namespace kiosk::platform {

/** @brief Text for an EGL error code ("EGL_BAD_MATCH"). */
const char* eglErrorName(EGLint error) noexcept;

/** @brief True if the client (display == EGL_NO_DISPLAY) or display extension string has `name`. */
bool hasEglExtension(EGLDisplay display, const char* name) noexcept;

/**
 * @brief Owns an initialised EGLDisplay and an ES 3 context; shared by every backend.
 * Destruction unbinds, destroys the surface (if set), the context, terminates the display.
 */
class EglContext {
public:
    EglContext() = default;
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    /**
     * @brief Initialise `display`, choose a config for `surfaceType` (EGL_PBUFFER_BIT,
     * EGL_WINDOW_BIT) with optional native visual id, create an ES 3.0+ context.
     * On failure fills `diags` with one PLATFORM_* error and returns false.
     */
    bool init(EGLDisplay display, EGLint surfaceType, EGLint nativeVisualId, const char* backend,
              Diagnostics& diags);
    /** @brief Create a window surface for `nativeWindow` and make everything current. */
    bool makeWindowCurrent(void* nativeWindow, const char* backend, Diagnostics& diags);
    /** @brief No surface: EGL_KHR_surfaceless_context. */
    bool makeSurfacelessCurrent(const char* backend, Diagnostics& diags);
    void setSwapInterval(int interval) noexcept;
    bool swap() noexcept;

    EGLDisplay display() const noexcept { return mDisplay; }
    EGLConfig config() const noexcept { return mConfig; }
    EGLSurface surface() const noexcept { return mSurface; }
    std::string version() const;

private:
    EGLDisplay mDisplay = EGL_NO_DISPLAY;
    EGLConfig mConfig = nullptr;
    EGLContext mContext = EGL_NO_CONTEXT;
    EGLSurface mSurface = EGL_NO_SURFACE;
};

}  // namespace kiosk::platform
