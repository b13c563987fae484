#include "runtime/anim/ScenarioClock.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace kiosk::anim {
namespace {

// Key times are epoch seconds (~1.8e9): a double resolves ~0.25 us there, and keys parsed from
// text or computed from offsets can land a few ulps off. One millisecond is far below any frame
// interval we will see and far above that noise.
constexpr double kKeyTolerance = 1e-3;

std::string pointer(std::string_view where, const char* member) {
    std::string s(where);
    s += '/';
    s += member;
    return s;
}

}  // namespace

Result<ScenarioClock> ScenarioClock::create(const ClockSettings& s, std::string_view file,
                                            std::string_view where) {
    Diagnostics d;
    const std::string f(file);
    auto requireFinite = [&](double v, const char* member) {
        if (!std::isfinite(v))
            d.error("ANIM_CLOCK_NOT_FINITE", f, pointer(where, member),
                    std::string("clock ") + member + " must be a finite time");
    };
    requireFinite(s.start, "start");
    requireFinite(s.end, "end");
    requireFinite(s.rate, "rate");
    if (s.initial) requireFinite(*s.initial, "initial");
    if (d.hasErrors()) return d;
    if (s.end < s.start) {
        d.error("ANIM_CLOCK_RANGE_INVERTED", f, std::string(where),
                "clock end " + formatIso8601(s.end) + " is before start " + formatIso8601(s.start));
        return d;
    }
    ScenarioClock c;
    c.mStart = s.start;
    c.mEnd = s.end;
    c.mRate = s.rate;
    c.mRange = s.range;
    c.mWaitForData = s.waitForData;
    c.mPaused = s.startPaused;
    c.mMaxWait = s.maxWaitSeconds;
    const double initial = s.initial ? *s.initial : (s.rate < 0.0 ? s.end : s.start);
    c.mTime = c.clampToRange(initial);
    if (c.mRange == RangeMode::Loop) c.mTime = c.wrapIntoLoop(c.mTime);
    return c;
}

double ScenarioClock::progress() const noexcept {
    const double span = mEnd - mStart;
    if (!(span > 0.0)) return 0.0;
    return std::clamp((mTime - mStart) / span, 0.0, 1.0);
}

void ScenarioClock::setRate(double rate) noexcept {
    if (std::isfinite(rate)) mRate = rate;
}

void ScenarioClock::setRangeMode(RangeMode mode) noexcept {
    mRange = mode;
    mTime = clampToRange(mTime);
}

double ScenarioClock::clampToRange(double t) const noexcept {
    if (mRange == RangeMode::Unbounded) return t;
    return std::clamp(t, mStart, mEnd);
}

double ScenarioClock::wrapIntoLoop(double t) const noexcept {
    const double span = mEnd - mStart;
    if (!(span > 0.0)) return mStart;
    if (mRate >= 0.0) {
        if (t >= mStart && t < mEnd) return t;
        double off = std::fmod(t - mStart, span);
        if (off < 0.0) off += span;
        // fmod of a value a hair below a multiple of span can round up to span itself.
        if (off >= span) off = 0.0;
        return mStart + off;
    }
    if (t > mStart && t <= mEnd) return t;
    double off = std::fmod(mEnd - t, span);
    if (off < 0.0) off += span;
    if (off >= span) off = 0.0;
    return mEnd - off;
}

bool ScenarioClock::seek(double epochSeconds) noexcept {
    if (!std::isfinite(epochSeconds)) return false;
    mTime = clampToRange(epochSeconds);
    mHeldWallSeconds = 0.0;  // a new target gets a fresh wait budget
    ++mSeekSerial;
    return true;
}

bool ScenarioClock::seekBy(double deltaSeconds) noexcept {
    if (!std::isfinite(deltaSeconds)) return false;
    const double t = mTime + deltaSeconds;
    if (mRange == RangeMode::Loop) {
        // Wrap in the direction of the scrub, so scrubbing backwards past start lands near end.
        const double span = mEnd - mStart;
        if (!(span > 0.0)) {
            mTime = mStart;
        } else if (t < mStart) {
            double off = std::fmod(mStart - t, span);
            mTime = off == 0.0 ? mStart : mEnd - off;
        } else if (t > mEnd) {
            double off = std::fmod(t - mEnd, span);
            mTime = off == 0.0 ? mEnd : mStart + off;
        } else {
            mTime = t;
        }
    } else {
        mTime = clampToRange(t);
    }
    mHeldWallSeconds = 0.0;
    ++mSeekSerial;
    return true;
}

bool ScenarioClock::stepToNextKey(std::span<const double> keyTimes) noexcept {
    const bool bounded = mRange != RangeMode::Unbounded;
    double best = std::numeric_limits<double>::infinity();
    double first = std::numeric_limits<double>::infinity();
    for (double k : keyTimes) {
        if (!std::isfinite(k)) continue;
        if (bounded && (k < mStart - kKeyTolerance || k > mEnd + kKeyTolerance)) continue;
        first = std::min(first, k);
        if (k > mTime + kKeyTolerance) best = std::min(best, k);
    }
    if (!std::isfinite(best)) {
        if (mRange != RangeMode::Loop || !std::isfinite(first)) return false;
        best = first;
    }
    return seek(best);
}

bool ScenarioClock::stepToPreviousKey(std::span<const double> keyTimes) noexcept {
    const bool bounded = mRange != RangeMode::Unbounded;
    double best = -std::numeric_limits<double>::infinity();
    double last = -std::numeric_limits<double>::infinity();
    for (double k : keyTimes) {
        if (!std::isfinite(k)) continue;
        if (bounded && (k < mStart - kKeyTolerance || k > mEnd + kKeyTolerance)) continue;
        last = std::max(last, k);
        if (k < mTime - kKeyTolerance) best = std::max(best, k);
    }
    if (!std::isfinite(best)) {
        if (mRange != RangeMode::Loop || !std::isfinite(last)) return false;
        best = last;
    }
    return seek(best);
}

bool ScenarioClock::canAdvance(double wallDeltaSeconds) const noexcept {
    return !mPaused && std::isfinite(wallDeltaSeconds) && wallDeltaSeconds > 0.0 && mRate != 0.0;
}

double ScenarioClock::predict(double wallDeltaSeconds) const noexcept {
    if (!canAdvance(wallDeltaSeconds)) return mTime;
    const double t = mTime + mRate * wallDeltaSeconds;
    switch (mRange) {
        case RangeMode::Loop:
            return wrapIntoLoop(t);
        case RangeMode::Clamp:
            return std::clamp(t, mStart, mEnd);
        case RangeMode::Unbounded:
            return t;
    }
    return t;
}

AdvanceResult ScenarioClock::advance(double wallDeltaSeconds, bool nextStepReady) noexcept {
    AdvanceResult r;
    r.time = mTime;
    auto atEnd = [&] {
        return mRange == RangeMode::Clamp &&
               ((mRate > 0.0 && mTime >= mEnd) || (mRate < 0.0 && mTime <= mStart));
    };
    if (!canAdvance(wallDeltaSeconds)) {
        r.atEnd = atEnd();
        return r;
    }
    if (!nextStepReady && mWaitForData) {
        const bool valve = std::isfinite(mMaxWait) && mMaxWait > 0.0;
        if (!valve || mHeldWallSeconds + wallDeltaSeconds <= mMaxWait) {
            mHeldWallSeconds += wallDeltaSeconds;
            ++mHeldTotal;
            ++mHeldInARow;
            r.held = true;
            r.atEnd = atEnd();
            return r;
        }
        ++mWaitTimeouts;
    }
    mHeldInARow = 0;
    mHeldWallSeconds = 0.0;
    const double t = mTime + mRate * wallDeltaSeconds;
    const double next = predict(wallDeltaSeconds);
    if (mRange == RangeMode::Loop && next != t) {
        r.wrapped = true;
        const double span = mEnd - mStart;
        // A huge wall delta (a stalled frame) can cross several loops at once.
        const double over = mRate > 0.0 ? t - mEnd : mStart - t;
        mLoops += span > 0.0 ? 1 + static_cast<std::uint64_t>(std::max(0.0, over) / span) : 1;
    }
    mTime = next;
    r.time = mTime;
    r.atEnd = atEnd();
    return r;
}

double timeForFrame(double t0, double t1, double fps, std::int64_t index, double rate) noexcept {
    if (!std::isfinite(t0) || !std::isfinite(t1) || !std::isfinite(fps) || !std::isfinite(rate) ||
        fps <= 0.0 || rate == 0.0 || index <= 0)
        return t0;
    const double step = std::fabs(rate) / fps;
    const double t =
        t1 >= t0 ? t0 + static_cast<double>(index) * step : t0 - static_cast<double>(index) * step;
    // Snap the final step onto t1 so a whole-step span ends exactly there despite rounding.
    if (std::fabs(t - t1) <= step * 1e-6) return t1;
    return t1 >= t0 ? std::min(t, t1) : std::max(t, t1);
}

std::int64_t frameCount(double t0, double t1, double fps, double rate) noexcept {
    if (!std::isfinite(t0) || !std::isfinite(t1) || !std::isfinite(fps) || !std::isfinite(rate) ||
        fps <= 0.0 || rate == 0.0)
        return 1;
    const double step = std::fabs(rate) / fps;
    // The relative epsilon keeps a span of exactly N steps from losing its last frame to rounding.
    const double steps = std::fabs(t1 - t0) / step;
    const double n = std::floor(steps * (1.0 + 1e-12) + 1e-9);
    if (n >= 9.0e15) return std::numeric_limits<std::int64_t>::max();
    return static_cast<std::int64_t>(n) + 1;
}

std::optional<RangeMode> parseRangeMode(std::string_view text) noexcept {
    if (text == "loop") return RangeMode::Loop;
    if (text == "clamp") return RangeMode::Clamp;
    if (text == "unbounded") return RangeMode::Unbounded;
    return std::nullopt;
}

const char* toString(RangeMode mode) noexcept {
    switch (mode) {
        case RangeMode::Loop:
            return "loop";
        case RangeMode::Clamp:
            return "clamp";
        case RangeMode::Unbounded:
            return "unbounded";
    }
    return "loop";
}

}  // namespace kiosk::anim
