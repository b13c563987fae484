#include "runtime/platform/Display.h"

#include <cstdlib>
#include <filesystem>

#include "runtime/platform/Backends.h"

namespace kiosk::platform {
namespace {

bool envSet(const char* name) {
    const char* v = std::getenv(name);
    return v && *v;
}

Result<std::unique_ptr<Display>> notBuilt(const char* name) {
    Diagnostics d;
    d.error("PLATFORM_NOT_BUILT", "", name,
            std::string("this geokiosk was built without the ") + name +
                " backend (CMake option KIOSK_PLATFORM_*)");
    return d;
}

}  // namespace

std::optional<DisplayKind> parseDisplayKind(const std::string& name) {
    if (name == "auto") return DisplayKind::Auto;
    if (name == "kms") return DisplayKind::Kms;
    if (name == "x11") return DisplayKind::X11;
    if (name == "wayland") return DisplayKind::Wayland;
    if (name == "headless") return DisplayKind::Headless;
    return std::nullopt;
}

const char* displayKindName(DisplayKind kind) noexcept {
    switch (kind) {
        case DisplayKind::Auto: return "auto";
        case DisplayKind::Kms: return "kms";
        case DisplayKind::X11: return "x11";
        case DisplayKind::Wayland: return "wayland";
        case DisplayKind::Headless: return "headless";
    }
    return "?";
}

bool backendAvailable(DisplayKind kind) noexcept {
    switch (kind) {
        case DisplayKind::Headless: return true;
#ifdef KIOSK_HAVE_X11
        case DisplayKind::X11: return true;
#endif
#ifdef KIOSK_HAVE_KMS
        case DisplayKind::Kms: return true;
#endif
#ifdef KIOSK_HAVE_WAYLAND
        case DisplayKind::Wayland: return true;
#endif
        default: return false;
    }
}

std::string findDrmDevice() {
    std::error_code ec;
    for (int i = 0; i < 16; ++i) {
        std::string path = "/dev/dri/card" + std::to_string(i);
        if (std::filesystem::exists(path, ec)) return path;
    }
    return {};
}

Result<std::unique_ptr<Display>> createDisplay(const DisplayOptions& options) {
    DisplayKind kind = options.kind;
    if (kind == DisplayKind::Auto) {
        if (envSet("WAYLAND_DISPLAY") && backendAvailable(DisplayKind::Wayland))
            kind = DisplayKind::Wayland;
        else if (envSet("DISPLAY") && backendAvailable(DisplayKind::X11))
            kind = DisplayKind::X11;
        else if (!findDrmDevice().empty() && backendAvailable(DisplayKind::Kms))
            kind = DisplayKind::Kms;
        else {
            Diagnostics d;
            d.error("PLATFORM_NO_DISPLAY", "", "",
                    "no display: DISPLAY and WAYLAND_DISPLAY are unset and there is no "
                    "/dev/dri/card* device")
                .hint = "use --display headless to render without one";
            return d;
        }
    }
    switch (kind) {
        case DisplayKind::Headless: return createSurfacelessDisplay(options);
        case DisplayKind::X11:
#ifdef KIOSK_HAVE_X11
            return createX11Display(options);
#else
            return notBuilt("x11");
#endif
        case DisplayKind::Kms:
#ifdef KIOSK_HAVE_KMS
            return createKmsDisplay(options);
#else
            return notBuilt("kms");
#endif
        case DisplayKind::Wayland:
#ifdef KIOSK_HAVE_WAYLAND
            return createWaylandDisplay(options);
#else
            return notBuilt("wayland");
#endif
        case DisplayKind::Auto: break;
    }
    return notBuilt("auto");
}

}  // namespace kiosk::platform
