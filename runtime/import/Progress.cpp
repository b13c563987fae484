#include "runtime/import/Progress.h"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace kiosk::import {

Progress::Progress(bool quiet) : mQuiet(quiet), mTty(isatty(STDERR_FILENO) == 1) {}

void Progress::begin(const std::string& label, std::int64_t total) {
    mLabel = label;
    mTotal = std::max<std::int64_t>(total, 1);
    mDone = 0;
    mLastDecile = -1;
    mStart = std::chrono::steady_clock::now();
    mLastDraw = {};
    draw(true);
}

void Progress::advance(std::int64_t n) {
    mDone += n;
    draw(false);
}

void Progress::finish() {
    mDone = mTotal;
    draw(true);
    if (!mQuiet && mTty) std::fputc('\n', stderr);
}

void Progress::draw(bool force) {
    if (mQuiet) return;
    const double frac = std::min(1.0, double(mDone) / double(mTotal));
    const auto now = std::chrono::steady_clock::now();
    if (mTty) {
        if (!force && now - mLastDraw < std::chrono::milliseconds(100)) return;
        mLastDraw = now;
        constexpr int kWidth = 30;
        const int filled = int(frac * kWidth);
        std::fprintf(stderr, "\r%-24.24s [%.*s%*s] %3d%% (%lld/%lld tiles)", mLabel.c_str(), filled,
                     "##############################", kWidth - filled, "", int(frac * 100),
                     (long long)mDone, (long long)mTotal);
        std::fflush(stderr);
    } else {
        // Logs get a line per 10 % once an import is slow enough to need one, and a last line.
        const int decile = int(frac * 10);
        const double secs = std::chrono::duration<double>(now - mStart).count();
        if (force && mDone >= mTotal) {
            std::fprintf(stderr, "%s: done, %lld tiles in %.1f s\n", mLabel.c_str(),
                         (long long)mDone, secs);
            return;
        }
        if (decile == mLastDecile || secs < 2.0) return;
        mLastDecile = decile;
        std::fprintf(stderr, "%s: %d%% (%lld/%lld tiles, %.1f s)\n", mLabel.c_str(), decile * 10,
                     (long long)mDone, (long long)mTotal, secs);
    }
}

}  // namespace kiosk::import
