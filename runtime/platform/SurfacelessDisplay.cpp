#include "runtime/platform/Backends.h"

#include "runtime/platform/EglCommon.h"

namespace kiosk::platform {
namespace {

class SurfacelessDisplay final : public Display {
public:
    SurfacelessDisplay(int w, int h) : mWidth(w), mHeight(h) {}
    DisplayKind kind() const noexcept override { return DisplayKind::Headless; }
    int width() const noexcept override { return mWidth; }
    int height() const noexcept override { return mHeight; }
    bool hasSurface() const noexcept override { return false; }
    bool swapBuffers() override { return true; }
    std::string describe() const override {
        return "headless " + std::to_string(mWidth) + "x" + std::to_string(mHeight) + " (EGL " +
               egl.version() + ", surfaceless)";
    }
    EglContext egl;

private:
    int mWidth, mHeight;
};

}  // namespace

Result<std::unique_ptr<Display>> createSurfacelessDisplay(const DisplayOptions& options) {
    Diagnostics diags;
    const char* backend = "headless";
    if (!hasEglExtension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
        diags.error("PLATFORM_NO_SURFACELESS", "", backend,
                    "EGL_MESA_platform_surfaceless is not available (install libegl-mesa0)");
        return diags;
    }
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) {
        diags.error("PLATFORM_NO_EGL_DISPLAY", "", backend, "eglGetPlatformDisplayEXT missing");
        return diags;
    }
    EGLDisplay dpy = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    auto display = std::make_unique<SurfacelessDisplay>(options.width > 0 ? options.width : 1280,
                                                        options.height > 0 ? options.height : 720);
    if (!display->egl.init(dpy, EGL_PBUFFER_BIT, 0, backend, diags)) return diags;
    if (!display->egl.makeSurfacelessCurrent(backend, diags)) return diags;
    return std::unique_ptr<Display>(std::move(display));
}

}  // namespace kiosk::platform
