#pragma once

#include "runtime/core/Clock.h"

#include <cstddef>
#include <cstdint>

namespace kiosk::loader {

/**
 * @brief Per-frame limit on GPU uploads (bytes and milliseconds) so a burst of arriving tiles
 * never makes one long frame. The render thread calls beginFrame() once per frame, then for each
 * candidate upload: `if (!budget.allow(bytes)) break;` ... upload ... `budget.consume(bytes);`.
 *
 * The first upload of a frame is always allowed, so a tile larger than the byte budget still
 * goes through (one per frame) instead of starving. Time is measured from beginFrame() with the
 * given clock (RealClock by default; FakeClock in tests). Render thread only; no allocation.
 */
class UploadBudget {
public:
    UploadBudget(std::size_t bytesPerFrame, double msPerFrame, const Clock* clock = nullptr);

    void beginFrame();
    /** @brief Whether an upload of `bytes` fits what is left of this frame's budget. */
    bool allow(std::size_t bytes) const;
    void consume(std::size_t bytes);

    std::size_t bytesUsed() const noexcept { return mBytes; }
    std::uint32_t uploads() const noexcept { return mUploads; }
    double msUsed() const;
    std::size_t bytesPerFrame() const noexcept { return mBytesPerFrame; }
    double msPerFrame() const noexcept { return mMsPerFrame; }
    void setLimits(std::size_t bytesPerFrame, double msPerFrame);

private:
    std::size_t mBytesPerFrame;
    double mMsPerFrame;
    const Clock* mClock;
    RealClock mRealClock;
    double mStart = 0.0;
    std::size_t mBytes = 0;
    std::uint32_t mUploads = 0;
};

}  // namespace kiosk::loader
