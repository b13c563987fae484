#include "runtime/core/Progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unistd.h>

namespace kiosk {

Progress::Progress(bool quiet, std::string unit)
    : mQuiet(quiet), mTty(isatty(STDERR_FILENO) == 1), mUnit(std::move(unit)) {}

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

std::string Progress::eta(double elapsedSeconds, std::int64_t done, std::int64_t total) {
    if (done <= 0 || elapsedSeconds <= 0) return "?";
    const double left =
        elapsedSeconds / double(done) * double(std::max<std::int64_t>(total - done, 0));
    const long s = std::lround(left);
    char buf[32];
    if (s >= 3600)
        std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, s / 60 % 60);
    else if (s >= 60)
        std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
    else
        std::snprintf(buf, sizeof buf, "%lds", s);
    return buf;
}

void Progress::draw(bool force) {
    if (mQuiet) return;
    const double frac = std::min(1.0, double(mDone) / double(mTotal));
    const auto now = std::chrono::steady_clock::now();
    const double secs = std::chrono::duration<double>(now - mStart).count();
    if (mTty) {
        if (!force && now - mLastDraw < std::chrono::milliseconds(100)) return;
        mLastDraw = now;
        constexpr int kWidth = 30;
        const int filled = int(frac * kWidth);
        std::fprintf(stderr, "\r%-24.24s [%.*s%*s] %3d%% (%lld/%lld %s) ETA %-8s", mLabel.c_str(),
                     filled, "##############################", kWidth - filled, "", int(frac * 100),
                     (long long)mDone, (long long)mTotal, mUnit.c_str(),
                     mDone >= mTotal ? "0s" : eta(secs, mDone, mTotal).c_str());
        std::fflush(stderr);
    } else {
        // Logs get a line per 10 % once a job is slow enough to need one, and a last line.
        const int decile = int(frac * 10);
        if (force && mDone >= mTotal) {
            std::fprintf(stderr, "%s: done, %lld %s in %.1f s\n", mLabel.c_str(), (long long)mDone,
                         mUnit.c_str(), secs);
            return;
        }
        if (decile == mLastDecile || decile >= 10 || secs < 2.0) return;
        mLastDecile = decile;
        std::fprintf(stderr, "%s: %d%% (%lld/%lld %s, %.1f s, ETA %s)\n", mLabel.c_str(),
                     decile * 10, (long long)mDone, (long long)mTotal, mUnit.c_str(), secs,
                     eta(secs, mDone, mTotal).c_str());
    }
}

}  // namespace kiosk
