// Backend selection and the one-line failures of backends that cannot run here (no DRM device,
// no X server): these run on every machine, with or without a GPU.
#include "runtime/platform/Display.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace kiosk::platform {
namespace {

bool drmCardExists() {
    std::error_code ec;
    for (int i = 0; i < 16; ++i)
        if (std::filesystem::exists("/dev/dri/card" + std::to_string(i), ec)) return true;
    return false;
}

int countLines(const std::string& text) {
    int n = 0;
    for (char c : text)
        if (c == '\n') ++n;
    return n;
}

/** @brief Sets (or unsets, with nullptr) an environment variable for one scope. */
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : mName(name) {
        if (const char* old = std::getenv(name)) mOld = old;
        if (value)
            setenv(name, value, 1);
        else
            unsetenv(name);
    }
    ~ScopedEnv() {
        if (mOld)
            setenv(mName, mOld->c_str(), 1);
        else
            unsetenv(mName);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* mName;
    std::optional<std::string> mOld;
};

/** @brief The failure contract of createDisplay(): one error, one line, the expected code. */
void expectOneLineFailure(const Result<std::unique_ptr<Display>>& r, const std::string& code,
                          const std::string& substring) {
    ASSERT_FALSE(r.ok());
    ASSERT_EQ(r.diagnostics.size(), 1u) << r.diagnostics.format();
    EXPECT_EQ(r.diagnostics.items()[0].code, code) << r.diagnostics.format();
    const std::string text = r.diagnostics.format();
    EXPECT_EQ(countLines(text), 1) << text;
    EXPECT_NE(text.find(substring), std::string::npos) << text;
}

TEST(DisplaySelection, ParseAndNameRoundTrip) {
    for (auto kind : {DisplayKind::Auto, DisplayKind::Kms, DisplayKind::X11, DisplayKind::Wayland,
                      DisplayKind::Headless}) {
        auto parsed = parseDisplayKind(displayKindName(kind));
        ASSERT_TRUE(parsed.has_value()) << displayKindName(kind);
        EXPECT_EQ(*parsed, kind);
    }
    EXPECT_FALSE(parseDisplayKind("").has_value());
    EXPECT_FALSE(parseDisplayKind("X11").has_value());  // names are lower case
    EXPECT_FALSE(parseDisplayKind("drm").has_value());
}

TEST(DisplaySelection, CompiledBackendsMatchCMakeOptions) {
    EXPECT_TRUE(backendAvailable(DisplayKind::Headless));
    EXPECT_EQ(backendAvailable(DisplayKind::X11), bool(KIOSK_TEST_HAVE_X11));
    EXPECT_EQ(backendAvailable(DisplayKind::Kms), bool(KIOSK_TEST_HAVE_KMS));
    EXPECT_EQ(backendAvailable(DisplayKind::Wayland), bool(KIOSK_TEST_HAVE_WAYLAND));
    EXPECT_FALSE(backendAvailable(DisplayKind::Auto));
}

TEST(DisplaySelection, KmsWithoutDrmDeviceFailsWithOneLine) {
    if (!backendAvailable(DisplayKind::Kms)) GTEST_SKIP() << "built without KIOSK_PLATFORM_KMS";
    if (drmCardExists())
        GTEST_SKIP() << "this machine has /dev/dri/card*: no-DRM path not testable";
    DisplayOptions opts;
    opts.kind = DisplayKind::Kms;
    auto r = createDisplay(opts);
    expectOneLineFailure(r, "PLATFORM_NO_DRM", "no DRM device: /dev/dri/card* does not exist");
    EXPECT_NE(r.diagnostics.format().find("GPU or a virtual display driver"), std::string::npos);
}

TEST(DisplaySelection, KmsNamedDeviceMissingNamesIt) {
    if (!backendAvailable(DisplayKind::Kms)) GTEST_SKIP() << "built without KIOSK_PLATFORM_KMS";
    const std::string path = "/dev/dri/card15";
    if (std::filesystem::exists(path)) GTEST_SKIP() << path << " exists";
    DisplayOptions opts;
    opts.kind = DisplayKind::Kms;
    opts.drmDevice = path;
    opts.connector = "HDMI-A-1";
    expectOneLineFailure(createDisplay(opts), "PLATFORM_NO_DRM",
                         "no DRM device: /dev/dri/card15 does not exist");
}

TEST(DisplaySelection, AutoWithNothingSaysNoDisplay) {
    if (drmCardExists()) GTEST_SKIP() << "this machine has /dev/dri/card*: auto would pick KMS";
    ScopedEnv noX("DISPLAY", nullptr);
    ScopedEnv noWayland("WAYLAND_DISPLAY", nullptr);
    DisplayOptions opts;  // kind = Auto
    auto r = createDisplay(opts);
    expectOneLineFailure(r, "PLATFORM_NO_DISPLAY", "no display");
    EXPECT_NE(r.diagnostics.format().find("--display headless"), std::string::npos)
        << r.diagnostics.format();
}

TEST(DisplaySelection, AutoPicksX11WhenDisplayIsSet) {
    if (!backendAvailable(DisplayKind::X11)) GTEST_SKIP() << "built without KIOSK_PLATFORM_X11";
    // No server listens on :4998, so the X11 backend's own error proves auto chose it.
    ScopedEnv x("DISPLAY", ":4998");
    ScopedEnv noWayland("WAYLAND_DISPLAY", nullptr);
    DisplayOptions opts;
    expectOneLineFailure(createDisplay(opts), "PLATFORM_X11_OPEN", "':4998'");
}

TEST(DisplaySelection, X11CannotOpenNamesDisplay) {
    if (!backendAvailable(DisplayKind::X11)) GTEST_SKIP() << "built without KIOSK_PLATFORM_X11";
    DisplayOptions opts;
    opts.kind = DisplayKind::X11;
    {
        ScopedEnv x("DISPLAY", ":4997");
        expectOneLineFailure(createDisplay(opts), "PLATFORM_X11_OPEN",
                             "cannot open X display ':4997' (from $DISPLAY)");
    }
    {
        ScopedEnv x("DISPLAY", nullptr);
        expectOneLineFailure(createDisplay(opts), "PLATFORM_X11_OPEN", "DISPLAY is not set");
    }
}

TEST(DisplaySelection, WaylandCannotConnectNamesSocket) {
    if (!backendAvailable(DisplayKind::Wayland))
        GTEST_SKIP() << "built without KIOSK_PLATFORM_WAYLAND";
    ScopedEnv w("WAYLAND_DISPLAY", "kiosk-no-such-socket");
    DisplayOptions opts;  // auto: WAYLAND_DISPLAY wins over DISPLAY
    expectOneLineFailure(createDisplay(opts), "PLATFORM_WAYLAND_CONNECT",
                         "cannot connect to Wayland display 'kiosk-no-such-socket'");
}

TEST(DisplaySelection, BackendNotBuiltSaysSo) {
    if (backendAvailable(DisplayKind::Wayland)) GTEST_SKIP() << "Wayland backend is built";
    DisplayOptions opts;
    opts.kind = DisplayKind::Wayland;
    expectOneLineFailure(createDisplay(opts), "PLATFORM_NOT_BUILT", "without the wayland backend");
}

}  // namespace
}  // namespace kiosk::platform
