#include "runtime/loader/UploadBudget.h"

namespace kiosk::loader {

UploadBudget::UploadBudget(std::size_t bytesPerFrame, double msPerFrame, const Clock* clock)
    : mBytesPerFrame(bytesPerFrame), mMsPerFrame(msPerFrame), mClock(clock ? clock : &mRealClock) {}

void UploadBudget::beginFrame() {
    mStart = mClock->now();
    mBytes = 0;
    mUploads = 0;
}

double UploadBudget::msUsed() const {
    return (mClock->now() - mStart) * 1000.0;
}

bool UploadBudget::allow(std::size_t bytes) const {
    if (mUploads == 0) return true;  // always make progress
    if (mBytes + bytes > mBytesPerFrame) return false;
    return msUsed() < mMsPerFrame;
}

void UploadBudget::consume(std::size_t bytes) {
    mBytes += bytes;
    ++mUploads;
}

void UploadBudget::setLimits(std::size_t bytesPerFrame, double msPerFrame) {
    mBytesPerFrame = bytesPerFrame;
    mMsPerFrame = msPerFrame;
}

}  // namespace kiosk::loader
