#include "runtime/core/Log.h"
#include "runtime/platform/Backends.h"
#include "runtime/platform/EglCommon.h"
#include "runtime/platform/KmsFlipLoop.h"
#include "runtime/platform/KmsSelection.h"

#include <gbm.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <memory>
#include <poll.h>
#include <unistd.h>
#include <vector>

// The GBM/KMS backend follows robclark/kmscube: pick connector, mode and CRTC, render into a
// GBM surface through EGL_PLATFORM_GBM_KHR, and present each frame with a page flip.
namespace kiosk::platform {
namespace {

constexpr const char* kBackend = "kms";
constexpr const char* kTag = "platform::KMS";
constexpr int kFlipTimeoutMs = 1000;  // a 1 Hz display still flips in time; a stuck one is caught
constexpr int kMaxCards = 16;

struct ResourcesDeleter {
    void operator()(drmModeRes* p) const noexcept { drmModeFreeResources(p); }
};
struct ConnectorDeleter {
    void operator()(drmModeConnector* p) const noexcept { drmModeFreeConnector(p); }
};
struct EncoderDeleter {
    void operator()(drmModeEncoder* p) const noexcept { drmModeFreeEncoder(p); }
};
using ResourcesPtr = std::unique_ptr<drmModeRes, ResourcesDeleter>;
using ConnectorPtr = std::unique_ptr<drmModeConnector, ConnectorDeleter>;
using EncoderPtr = std::unique_ptr<drmModeEncoder, EncoderDeleter>;

/** @brief "HDMI-A-1", the name the kernel and every compositor use for a connector. */
std::string connectorName(const drmModeConnector& c) {
    const char* type = drmModeGetConnectorTypeName(c.connector_type);
    return std::string(type ? type : "Unknown") + "-" + std::to_string(c.connector_type_id);
}

kms::ModeInfo modeInfo(const drmModeModeInfo& m) {
    return {int(m.hdisplay), int(m.vdisplay), int(m.vrefresh),
            (m.type & DRM_MODE_TYPE_PREFERRED) != 0};
}

std::string modeName(const drmModeModeInfo& m) {
    return kms::modeName(modeInfo(m));
}

/** @brief Framebuffer id cached on a scanout bo; freed by GBM when the bo is destroyed. */
struct BoFramebuffer {
    int fd = -1;
    std::uint32_t id = 0;
};

void destroyBoFramebuffer(gbm_bo* bo, void* data) {
    (void)bo;
    auto* fb = static_cast<BoFramebuffer*>(data);
    if (fb->id) drmModeRmFB(fb->fd, fb->id);
    delete fb;
}

// The display owns the DRM/GBM objects and lends them to the flip loop as its KmsDevice.
class KmsDisplay final : public Display, private KmsDevice {
public:
    KmsDisplay() = default;
    ~KmsDisplay() override;

    DisplayKind kind() const noexcept override { return DisplayKind::Kms; }
    int width() const noexcept override { return mMode.hdisplay; }
    int height() const noexcept override { return mMode.vdisplay; }
    bool swapBuffers() override;
    std::string describe() const override {
        return "kms " + mDevice + " " + mConnectorName + " " + modeName(mMode) + " (EGL " +
               mEgl->version() + ")";
    }

    bool create(const DisplayOptions& options, Diagnostics& diags);

private:
    bool openDevice(const DisplayOptions& options, Diagnostics& diags);
    bool chooseConnector(const std::string& wanted, Diagnostics& diags);
    bool chooseMode(int width, int height, Diagnostics& diags);
    bool chooseCrtc(Diagnostics& diags);
    bool createEgl(Diagnostics& diags);
    // KmsDevice
    Buffer lockFrontBuffer() override { return gbm_surface_lock_front_buffer(mSurface); }
    void releaseBuffer(Buffer b) override {
        gbm_surface_release_buffer(mSurface, static_cast<gbm_bo*>(b));
    }
    std::uint32_t framebufferFor(Buffer b) override;
    bool setMode(std::uint32_t fb) override;
    bool pageFlip(std::uint32_t fb) override;
    Wait waitForFlip(int timeoutMs) override;
    bool connectorConnected() override;
    static void onPageFlip(int fd, unsigned sequence, unsigned sec, unsigned usec, void* user);

    std::string mDevice;
    int mFd = -1;
    bool mBecameMaster = false;
    ResourcesPtr mResources;
    ConnectorPtr mConnector;
    std::string mConnectorName;
    drmModeModeInfo mMode{};
    std::uint32_t mCrtcId = 0;
    drmModeCrtc* mSavedCrtc = nullptr;
    gbm_device* mGbm = nullptr;
    gbm_surface* mSurface = nullptr;
    std::unique_ptr<EglContext> mEgl = std::make_unique<EglContext>();
    KmsFlipLoop mFlips{*this, kFlipTimeoutMs};
    bool mFlipDone = false;
    bool mWarnedTimeout = false;
};

KmsDisplay::~KmsDisplay() {
    // Reverse order of create(): let the last flip land, give the CRTC back, release the
    // buffers, then EGL (its surface wraps the GBM surface), GBM, master and the device.
    if (mSurface) mFlips.settle();
    if (mSavedCrtc) {
        if (mFlips.modeSet() && mSavedCrtc->mode_valid) {
            std::uint32_t connector = mConnector->connector_id;
            drmModeSetCrtc(mFd, mSavedCrtc->crtc_id, mSavedCrtc->buffer_id, mSavedCrtc->x,
                           mSavedCrtc->y, &connector, 1, &mSavedCrtc->mode);
        } else if (mFlips.modeSet()) {
            // The CRTC was off before us: switch it off again rather than leave our buffer.
            drmModeSetCrtc(mFd, mSavedCrtc->crtc_id, 0, 0, 0, nullptr, 0, nullptr);
        }
        drmModeFreeCrtc(mSavedCrtc);
    }
    if (mSurface) mFlips.releaseAll();
    mEgl.reset();
    if (mSurface) gbm_surface_destroy(mSurface);
    if (mGbm) gbm_device_destroy(mGbm);
    mConnector.reset();
    mResources.reset();
    if (mFd >= 0) {
        if (mBecameMaster) drmDropMaster(mFd);
        close(mFd);
    }
}

bool KmsDisplay::openDevice(const DisplayOptions& options, Diagnostics& diags) {
    std::vector<std::string> candidates;
    std::error_code ec;
    if (!options.drmDevice.empty()) {
        if (!std::filesystem::exists(options.drmDevice, ec)) {
            diags
                .error("PLATFORM_NO_DRM", "", kBackend,
                       "no DRM device: " + options.drmDevice + " does not exist")
                .hint = "the KMS backend needs a GPU or a virtual display driver";
            return false;
        }
        candidates.push_back(options.drmDevice);
    } else {
        for (int i = 0; i < kMaxCards; ++i) {
            std::string path = "/dev/dri/card" + std::to_string(i);
            if (std::filesystem::exists(path, ec)) candidates.push_back(path);
        }
        if (candidates.empty()) {
            diags
                .error("PLATFORM_NO_DRM", "", kBackend,
                       "no DRM device: /dev/dri/card* does not exist")
                .hint = "the KMS backend needs a GPU or a virtual display driver";
            return false;
        }
    }

    // Several cards are common on ARM boards (Raspberry Pi: v3d renders, vc4 displays): take
    // the first with a connected output, else the first with any connector (to report on).
    std::string firstOpenError;
    for (const auto& path : candidates) {
        int fd = open(path.c_str(), O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            if (firstOpenError.empty())
                firstOpenError = "cannot open " + path + ": " + std::strerror(errno);
            continue;
        }
        ResourcesPtr res(drmModeGetResources(fd));
        if (!res || res->count_connectors == 0) {
            close(fd);
            continue;
        }
        bool connected = false;
        for (int i = 0; i < res->count_connectors && !connected; ++i) {
            ConnectorPtr c(drmModeGetConnector(fd, res->connectors[i]));
            connected = c && c->connection == DRM_MODE_CONNECTED && c->count_modes > 0;
        }
        if (mFd < 0 || connected) {
            if (mFd >= 0) close(mFd);
            mFd = fd;
            mDevice = path;
            mResources = std::move(res);
            if (connected) break;
        } else {
            close(fd);
        }
    }
    if (mFd < 0) {
        if (!firstOpenError.empty()) {
            diags.error("PLATFORM_DRM_OPEN", "", kBackend, firstOpenError).hint =
                "the user needs the 'video' group";
        } else {
            diags.error("PLATFORM_DRM_NOT_KMS", "", kBackend,
                        "no KMS output: " + candidates.front() +
                            (candidates.size() > 1 ? " (and the other cards) have" : " has") +
                            " no display connectors");
        }
        return false;
    }

    // Opening a card nobody else holds makes us master; otherwise ask (fails while a desktop
    // session or another kiosk owns the outputs).
    if (drmIsMaster(mFd) == 0) {
        if (drmSetMaster(mFd) != 0) {
            diags
                .error("PLATFORM_DRM_MASTER", "", kBackend,
                       "cannot become DRM master on " + mDevice + ": " + std::strerror(errno))
                .hint =
                "another compositor or X server owns the display; stop it or use "
                "--display x11";
            return false;
        }
        mBecameMaster = true;
    }
    return true;
}

bool KmsDisplay::chooseConnector(const std::string& wanted, Diagnostics& diags) {
    std::vector<ConnectorPtr> connectors;
    std::vector<kms::ConnectorInfo> infos;
    for (int i = 0; i < mResources->count_connectors; ++i) {
        ConnectorPtr c(drmModeGetConnector(mFd, mResources->connectors[i]));
        if (!c) continue;
        kms::ConnectorInfo info;
        info.name = connectorName(*c);
        info.connected = c->connection == DRM_MODE_CONNECTED;
        for (int m = 0; m < c->count_modes; ++m) info.modes.push_back(modeInfo(c->modes[m]));
        infos.push_back(std::move(info));
        connectors.push_back(std::move(c));
    }
    const int index = kms::chooseConnector(infos, wanted, mDevice, diags);
    if (index < 0) return false;
    mConnectorName = infos[std::size_t(index)].name;
    mConnector = std::move(connectors[std::size_t(index)]);
    return true;
}

bool KmsDisplay::chooseMode(int width, int height, Diagnostics& diags) {
    std::vector<kms::ModeInfo> modes;
    for (int i = 0; i < mConnector->count_modes; ++i)
        modes.push_back(modeInfo(mConnector->modes[i]));
    const int index = kms::chooseMode(modes, width, height, mConnectorName, diags);
    if (index < 0) return false;
    mMode = mConnector->modes[index];
    return true;
}

bool KmsDisplay::chooseCrtc(Diagnostics& diags) {
    // The CRTC already driving this connector keeps the console's timing; otherwise the first
    // CRTC any of its encoders can reach.
    if (mConnector->encoder_id) {
        EncoderPtr enc(drmModeGetEncoder(mFd, mConnector->encoder_id));
        if (enc && enc->crtc_id) {
            mCrtcId = enc->crtc_id;
            return true;
        }
    }
    for (int e = 0; e < mConnector->count_encoders; ++e) {
        EncoderPtr enc(drmModeGetEncoder(mFd, mConnector->encoders[e]));
        if (!enc) continue;
        for (int c = 0; c < mResources->count_crtcs; ++c) {
            if (enc->possible_crtcs & (1u << c)) {
                mCrtcId = mResources->crtcs[c];
                return true;
            }
        }
    }
    diags.error("PLATFORM_DRM_CRTC", "", kBackend,
                "no CRTC can drive " + mConnectorName + " on " + mDevice);
    return false;
}

bool KmsDisplay::createEgl(Diagnostics& diags) {
    mGbm = gbm_create_device(mFd);
    if (!mGbm) {
        diags.error("PLATFORM_GBM", "", kBackend, "cannot create a GBM device on " + mDevice);
        return false;
    }
    mSurface = gbm_surface_create(mGbm, mMode.hdisplay, mMode.vdisplay, GBM_FORMAT_XRGB8888,
                                  GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    if (!mSurface) {
        diags.error(
            "PLATFORM_GBM", "", kBackend,
            "cannot create a " + modeName(mMode) + " XRGB8888 scanout surface on " + mDevice);
        return false;
    }
    EGLDisplay dpy = EGL_NO_DISPLAY;
    if (hasEglExtension(EGL_NO_DISPLAY, "EGL_KHR_platform_gbm") ||
        hasEglExtension(EGL_NO_DISPLAY, "EGL_MESA_platform_gbm")) {
        auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
            eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (getPlatformDisplay) dpy = getPlatformDisplay(EGL_PLATFORM_GBM_KHR, mGbm, nullptr);
    }
    if (dpy == EGL_NO_DISPLAY) dpy = eglGetDisplay(reinterpret_cast<EGLNativeDisplayType>(mGbm));
    if (!mEgl->init(dpy, EGL_WINDOW_BIT, EGLint(GBM_FORMAT_XRGB8888), kBackend, diags))
        return false;
    // EglContext falls back to its first config; scanout needs exactly XRGB8888.
    EGLint visual = 0;
    eglGetConfigAttrib(mEgl->display(), mEgl->config(), EGL_NATIVE_VISUAL_ID, &visual);
    if (visual != EGLint(GBM_FORMAT_XRGB8888)) {
        diags.error("PLATFORM_NO_CONFIG", "", kBackend,
                    "no EGL config renders to XRGB8888 GBM buffers on " + mDevice);
        return false;
    }
    return mEgl->makeWindowCurrent(reinterpret_cast<void*>(mSurface), kBackend, diags);
}

bool KmsDisplay::create(const DisplayOptions& options, Diagnostics& diags) {
    if (!openDevice(options, diags)) return false;
    if (!chooseConnector(options.connector, diags)) return false;
    if (!chooseMode(options.width, options.height, diags)) return false;
    if (!chooseCrtc(diags)) return false;
    mSavedCrtc = drmModeGetCrtc(mFd, mCrtcId);
    if (!createEgl(diags)) return false;
    // Page flips complete on vblank: KMS presentation is always vsynced, whatever options.vsync
    // says (eglSwapInterval has no effect on GBM surfaces).
    KIOSK_LOG_INFO(kTag, "%s", describe().c_str());
    return true;
}

std::uint32_t KmsDisplay::framebufferFor(Buffer buffer) {
    auto* bo = static_cast<gbm_bo*>(buffer);
    if (auto* fb = static_cast<BoFramebuffer*>(gbm_bo_get_user_data(bo))) return fb->id;
    auto* fb = new BoFramebuffer{mFd, 0};
    const int rc = drmModeAddFB(mFd, gbm_bo_get_width(bo), gbm_bo_get_height(bo), 24, 32,
                                gbm_bo_get_stride(bo), gbm_bo_get_handle(bo).u32, &fb->id);
    if (rc != 0) {
        KIOSK_LOG_ERROR(kTag, "drmModeAddFB failed on %s: %s", mDevice.c_str(),
                        std::strerror(errno));
        delete fb;
        return 0;
    }
    gbm_bo_set_user_data(bo, fb, destroyBoFramebuffer);
    return fb->id;
}

bool KmsDisplay::setMode(std::uint32_t fb) {
    std::uint32_t connector = mConnector->connector_id;
    if (drmModeSetCrtc(mFd, mCrtcId, fb, 0, 0, &connector, 1, &mMode) == 0) return true;
    KIOSK_LOG_ERROR(kTag, "cannot set mode %s on %s %s: %s", modeName(mMode).c_str(),
                    mDevice.c_str(), mConnectorName.c_str(), std::strerror(errno));
    return false;
}

bool KmsDisplay::pageFlip(std::uint32_t fb) {
    mFlipDone = false;
    if (drmModePageFlip(mFd, mCrtcId, fb, DRM_MODE_PAGE_FLIP_EVENT, this) == 0) return true;
    KIOSK_LOG_ERROR(kTag, "page flip on %s failed: %s", mDevice.c_str(), std::strerror(errno));
    return false;
}

bool KmsDisplay::connectorConnected() {
    // drmModeGetConnectorCurrent reads the state the kernel has, without a slow probe.
    ConnectorPtr c(drmModeGetConnectorCurrent(mFd, mConnector->connector_id));
    return c && c->connection == DRM_MODE_CONNECTED;
}

void KmsDisplay::onPageFlip(int fd, unsigned sequence, unsigned sec, unsigned usec, void* user) {
    (void)fd;
    (void)sequence;
    (void)sec;
    (void)usec;
    static_cast<KmsDisplay*>(user)->mFlipDone = true;
}

KmsDevice::Wait KmsDisplay::waitForFlip(int timeoutMs) {
    drmEventContext ctx{};
    ctx.version = 2;  // page_flip_handler is all we need
    ctx.page_flip_handler = onPageFlip;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeoutMs);
    while (!mFlipDone) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                              deadline - std::chrono::steady_clock::now())
                              .count();
        if (left <= 0) return Wait::Timeout;
        pollfd pfd{mFd, POLLIN, 0};
        const int rc = poll(&pfd, 1, int(left));
        if (rc < 0 && errno != EINTR) {
            KIOSK_LOG_ERROR(kTag, "poll on %s failed: %s", mDevice.c_str(), std::strerror(errno));
            return Wait::Error;
        }
        if (rc > 0) drmHandleEvent(mFd, &ctx);
    }
    return Wait::Flipped;
}

bool KmsDisplay::swapBuffers() {
    if (!mEgl->swap()) return false;
    if (mFlips.present()) {
        mWarnedTimeout = false;
        return true;
    }
    // Log once per episode: a display that stays stuck must not flood the journal.
    if (!mWarnedTimeout || mFlips.unplugged())
        KIOSK_LOG_ERROR(kTag, "%s %s: %s", mDevice.c_str(), mConnectorName.c_str(),
                        mFlips.error().c_str());
    mWarnedTimeout = true;
    return false;
}

}  // namespace

Result<std::unique_ptr<Display>> createKmsDisplay(const DisplayOptions& options) {
    Diagnostics diags;
    auto display = std::make_unique<KmsDisplay>();
    if (!display->create(options, diags)) return diags;
    return std::unique_ptr<Display>(std::move(display));
}

}  // namespace kiosk::platform
