#include "runtime/platform/EglCommon.h"

#include <cstring>
#include <vector>

namespace kiosk::platform {

const char* eglErrorName(EGLint error) noexcept {
    switch (error) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
        case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
        default: return "EGL error";
    }
}

bool hasEglExtension(EGLDisplay display, const char* name) noexcept {
    const char* exts = eglQueryString(display, EGL_EXTENSIONS);
    if (!exts) return false;
    const std::size_t len = std::strlen(name);
    for (const char* p = exts; (p = std::strstr(p, name)) != nullptr; p += len) {
        if ((p == exts || p[-1] == ' ') && (p[len] == ' ' || p[len] == '\0')) return true;
    }
    return false;
}

EglContext::~EglContext() {
    if (mDisplay == EGL_NO_DISPLAY) return;
    eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (mSurface != EGL_NO_SURFACE) eglDestroySurface(mDisplay, mSurface);
    if (mContext != EGL_NO_CONTEXT) eglDestroyContext(mDisplay, mContext);
    eglTerminate(mDisplay);
    eglReleaseThread();
}

bool EglContext::init(EGLDisplay display, EGLint surfaceType, EGLint nativeVisualId,
                      const char* backend, Diagnostics& diags) {
    if (display == EGL_NO_DISPLAY) {
        diags.error("PLATFORM_NO_EGL_DISPLAY", "", backend, "no EGL display available");
        return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        diags.error("PLATFORM_EGL_INIT", "", backend,
                    std::string("cannot initialise EGL: ") + eglErrorName(eglGetError()));
        return false;
    }
    mDisplay = display;
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        diags.error("PLATFORM_NO_GLES", "", backend, "EGL has no OpenGL ES support");
        return false;
    }
    const EGLint attribs[] = {EGL_SURFACE_TYPE, surfaceType, EGL_RENDERABLE_TYPE,
                              EGL_OPENGL_ES3_BIT_KHR, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                              EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, surfaceType == EGL_PBUFFER_BIT ? 0 : 24,
                              EGL_NONE};
    EGLint count = 0;
    eglChooseConfig(display, attribs, nullptr, 0, &count);
    if (count <= 0) {
        diags.error("PLATFORM_NO_CONFIG", "", backend,
                    "no EGL config with OpenGL ES 3 and 8-bit RGB");
        return false;
    }
    std::vector<EGLConfig> configs(static_cast<std::size_t>(count));
    eglChooseConfig(display, attribs, configs.data(), count, &count);
    mConfig = configs[0];
    if (nativeVisualId != 0) {
        // GBM and X11 need the config whose visual matches the surface format exactly.
        for (EGLConfig c : configs) {
            EGLint id = 0;
            if (eglGetConfigAttrib(display, c, EGL_NATIVE_VISUAL_ID, &id) && id == nativeVisualId) {
                mConfig = c;
                break;
            }
        }
    }
    const EGLint ctxAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0,
                                 EGL_NONE};
    mContext = eglCreateContext(display, mConfig, EGL_NO_CONTEXT, ctxAttribs);
    if (mContext == EGL_NO_CONTEXT) {
        diags.error("PLATFORM_NO_GLES3", "", backend,
                    std::string("cannot create an OpenGL ES 3.0 context: ") +
                        eglErrorName(eglGetError()));
        return false;
    }
    return true;
}

bool EglContext::makeWindowCurrent(void* nativeWindow, const char* backend, Diagnostics& diags) {
    mSurface = eglCreateWindowSurface(mDisplay, mConfig,
                                      reinterpret_cast<EGLNativeWindowType>(nativeWindow), nullptr);
    if (mSurface == EGL_NO_SURFACE) {
        diags.error("PLATFORM_NO_SURFACE", "", backend,
                    std::string("cannot create a window surface: ") + eglErrorName(eglGetError()));
        return false;
    }
    if (!eglMakeCurrent(mDisplay, mSurface, mSurface, mContext)) {
        diags.error("PLATFORM_MAKE_CURRENT", "", backend,
                    std::string("cannot make the context current: ") + eglErrorName(eglGetError()));
        return false;
    }
    return true;
}

bool EglContext::makeSurfacelessCurrent(const char* backend, Diagnostics& diags) {
    if (!eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, mContext)) {
        diags.error("PLATFORM_MAKE_CURRENT", "", backend,
                    std::string("cannot make a surfaceless context current: ") +
                        eglErrorName(eglGetError()));
        return false;
    }
    return true;
}

void EglContext::setSwapInterval(int interval) noexcept {
    if (mDisplay != EGL_NO_DISPLAY) eglSwapInterval(mDisplay, interval);
}

bool EglContext::swap() noexcept {
    return mSurface != EGL_NO_SURFACE && eglSwapBuffers(mDisplay, mSurface) == EGL_TRUE;
}

std::string EglContext::version() const {
    const char* v = mDisplay != EGL_NO_DISPLAY ? eglQueryString(mDisplay, EGL_VERSION) : nullptr;
    return v ? v : "?";
}

}  // namespace kiosk::platform
