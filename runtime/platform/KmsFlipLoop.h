#pragma once

#include <cstdint>
#include <string>

// The page-flip loop of the KMS backend, apart from DRM/GBM so that it can be tested against a
// fake device: one blocking mode set on the first frame, then one page flip per frame waited
// for on its vblank event, each buffer handed back to GBM once the next one is on screen, and a
// connector unplug noticed when a flip fails or times out. No DRM headers here.
namespace kiosk::platform {

/** @brief The DRM/GBM operations the loop needs (KmsDisplay.cpp implements them). */
class KmsDevice {
public:
    using Buffer = void*;  ///< a locked GBM front buffer (gbm_bo*), opaque to the loop
    enum class Wait { Flipped, Timeout, Error };

    virtual ~KmsDevice() = default;
    /** @brief gbm_surface_lock_front_buffer after eglSwapBuffers; nullptr on failure. */
    virtual Buffer lockFrontBuffer() = 0;
    /** @brief gbm_surface_release_buffer: the buffer may be rendered into again. */
    virtual void releaseBuffer(Buffer buffer) = 0;
    /** @brief DRM framebuffer id for a buffer (created once per buffer); 0 on failure. */
    virtual std::uint32_t framebufferFor(Buffer buffer) = 0;
    /** @brief drmModeSetCrtc with the chosen mode and connector (blocking). */
    virtual bool setMode(std::uint32_t framebuffer) = 0;
    /** @brief drmModePageFlip with a completion event. */
    virtual bool pageFlip(std::uint32_t framebuffer) = 0;
    /** @brief Wait up to `timeoutMs` for the pending flip's vblank event. */
    virtual Wait waitForFlip(int timeoutMs) = 0;
    /** @brief The connector still reports a display (cheap: no probing). */
    virtual bool connectorConnected() = 0;
};

class KmsFlipLoop {
public:
    KmsFlipLoop(KmsDevice& device, int flipTimeoutMs)
        : mDevice(device), mFlipTimeoutMs(flipTimeoutMs) {}

    /**
     * @brief Present the frame EGL just swapped: mode set on the first frame, else page flip and
     * wait for it. False when the frame could not be presented; `error()` says why and
     * `unplugged()` tells a connector unplug from other failures.
     */
    bool present();
    /** @brief Teardown, step 1: let a pending flip land (then restore the CRTC). */
    void settle();
    /** @brief Teardown, step 2 (once the CRTC no longer scans our buffers): give them back. */
    void releaseAll();

    bool modeSet() const noexcept { return mModeSet; }
    bool unplugged() const noexcept { return mUnplugged; }
    const std::string& error() const noexcept { return mError; }
    std::uint64_t flips() const noexcept { return mFlips; }
    std::uint64_t buffersReleased() const noexcept { return mReleased; }

private:
    bool waitPending();
    void release(KmsDevice::Buffer& b);
    bool fail(std::string why);

    KmsDevice& mDevice;
    int mFlipTimeoutMs;
    KmsDevice::Buffer mScanout = nullptr;  ///< on screen now
    KmsDevice::Buffer mPending = nullptr;  ///< queued by a flip that has not landed
    bool mModeSet = false;
    bool mUnplugged = false;
    std::string mError;
    std::uint64_t mFlips = 0;
    std::uint64_t mReleased = 0;
};

}  // namespace kiosk::platform
