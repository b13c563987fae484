#include "runtime/platform/KmsFlipLoop.h"

namespace kiosk::platform {

void KmsFlipLoop::release(KmsDevice::Buffer& b) {
    if (!b) return;
    mDevice.releaseBuffer(b);
    b = nullptr;
    ++mReleased;
}

bool KmsFlipLoop::fail(std::string why) {
    // A failed flip or a flip that never lands is what an unplugged connector looks like.
    mUnplugged = !mDevice.connectorConnected();
    mError = mUnplugged ? "the display was unplugged (" + why + ")" : std::move(why);
    return false;
}

bool KmsFlipLoop::waitPending() {
    if (!mPending) return true;
    switch (mDevice.waitForFlip(mFlipTimeoutMs)) {
        case KmsDevice::Wait::Flipped:
            // The flip landed: the previous buffer is no longer scanned out and goes back to GBM.
            release(mScanout);
            mScanout = mPending;
            mPending = nullptr;
            return true;
        case KmsDevice::Wait::Timeout:
            return fail("page flip did not complete within " + std::to_string(mFlipTimeoutMs) +
                        " ms");
        case KmsDevice::Wait::Error:
            break;
    }
    return fail("waiting for the page flip failed");
}

bool KmsFlipLoop::present() {
    mError.clear();
    // A flip that timed out last frame may still land; never queue a second one behind it.
    if (!waitPending()) return false;
    KmsDevice::Buffer next = mDevice.lockFrontBuffer();
    if (!next) return fail("no front buffer to present (gbm_surface_lock_front_buffer failed)");
    const std::uint32_t fb = mDevice.framebufferFor(next);
    if (!fb) {
        release(next);
        return fail("cannot make a DRM framebuffer for the frame");
    }
    if (!mModeSet) {
        // First frame: a blocking mode set puts our buffer on the CRTC; flips follow.
        if (!mDevice.setMode(fb)) {
            release(next);
            return fail("mode set failed");
        }
        mModeSet = true;
        mScanout = next;
        return true;
    }
    if (!mDevice.pageFlip(fb)) {
        release(next);
        return fail("page flip failed");
    }
    mPending = next;
    ++mFlips;
    return waitPending();
}

void KmsFlipLoop::settle() {
    if (mPending && mDevice.waitForFlip(mFlipTimeoutMs) == KmsDevice::Wait::Flipped) {
        release(mScanout);
        mScanout = mPending;
        mPending = nullptr;
    }
}

void KmsFlipLoop::releaseAll() {
    release(mPending);
    release(mScanout);
}

}  // namespace kiosk::platform
