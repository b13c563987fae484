#pragma once

#include "runtime/core/Result.h"
#include "runtime/core/TimeParse.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace kiosk::anim {

/** @brief What the clock does at the ends of its [start, end] range. */
enum class RangeMode {
    Loop,      ///< wrap: past the end continue at the start (at the end when the rate is negative)
    Clamp,     ///< stop at the end in the playback direction (time holds there)
    Unbounded  ///< no limit; start/end still anchor offsets and key stepping
};

/** @brief Settings a scenario gives its clock (all times UTC epoch seconds). */
struct ClockSettings {
    double start = 0.0;
    double end = 0.0;
    double rate = 1.0;  ///< data seconds per wall second; negative plays backwards, 0 freezes
    RangeMode range = RangeMode::Loop;
    /** @brief CesiumJS canAnimate semantics: if the next step is not ready, data time holds. */
    bool waitForData = true;
    /** @brief Initial time; when unset: start, or end for a negative rate. */
    std::optional<double> initial;
    bool startPaused = false;
    /**
     * @brief Safety valve for waitForData: after holding this many wall seconds in a row the
     * clock moves on anyway (the screen still never mixes times, see VisiblePair), so a tile
     * that never arrives cannot freeze a kiosk. <= 0 or non-finite: wait forever.
     */
    double maxWaitSeconds = 5.0;
};

/** @brief What one `advance` did. */
struct AdvanceResult {
    double time = 0.0;     ///< data time after the call
    bool held = false;     ///< true if data time was held because the next step was not ready
    bool wrapped = false;  ///< true if a loop boundary was crossed
    bool atEnd = false;    ///< Clamp mode: sitting on the end in the playback direction
};

/**
 * @brief The scenario clock: data time driven by wall time, a rate and a range behaviour.
 *
 * Thread: not thread-safe; owned by the render thread and advanced once per frame.
 * Bad input: non-finite arguments to seek/advance are ignored (the call returns false / holds);
 * invalid settings are rejected by `create` with a Diagnostic, never an abort.
 *
 * Loop semantics: with a positive rate data time stays in [start, end) (reaching `end` wraps to
 * `start`), with a negative rate in (start, end]. A zero-length loop pins time to `start`.
 */
class ScenarioClock {
public:
    /** @brief A clock on [0, 0], rate 1, looping. Prefer `create`. */
    ScenarioClock() = default;

    /**
     * @brief Validate settings and build a clock.
     * Errors: ANIM_CLOCK_NOT_FINITE (start/end/rate/initial NaN or infinite), ANIM_CLOCK_RANGE_
     * INVERTED (end < start). `file` and `where` (JSON pointer of the clock object) locate the
     * culprit in the message.
     */
    static Result<ScenarioClock> create(const ClockSettings& settings, std::string_view file = {},
                                        std::string_view where = "/clock");

    double start() const noexcept { return mStart; }
    double end() const noexcept { return mEnd; }
    double current() const noexcept { return mTime; }
    /** @brief Seconds since start (negative before it). */
    double elapsed() const noexcept { return mTime - mStart; }
    /** @brief Fraction of [start, end] in [0, 1] (for a progress bar); 0 for an empty range. */
    double progress() const noexcept;

    double rate() const noexcept { return mRate; }
    /** @brief Ignores non-finite values. The current time is kept. */
    void setRate(double rate) noexcept;
    RangeMode rangeMode() const noexcept { return mRange; }
    void setRangeMode(RangeMode mode) noexcept;
    bool waitForData() const noexcept { return mWaitForData; }
    void setWaitForData(bool wait) noexcept { mWaitForData = wait; }

    bool paused() const noexcept { return mPaused; }
    void pause() noexcept { mPaused = true; }
    void resume() noexcept { mPaused = false; }
    void togglePause() noexcept { mPaused = !mPaused; }

    /**
     * @brief Jump to an absolute time. In Loop and Clamp modes the target is clamped into
     * [start, end] (jumping "past the end" lands on the end, it does not wrap). Returns false
     * (and changes nothing) for a non-finite time. Bumps `seekSerial`.
     */
    bool seek(double epochSeconds) noexcept;
    /** @brief Seek to a TimeSpec: absolute, or an offset from `start` (docs/cli.md). */
    bool seek(const TimeSpec& spec) noexcept { return seek(spec.resolve(mStart)); }
    /** @brief Scrub by `deltaSeconds` from the current time: wraps in Loop, clamps in Clamp. */
    bool seekBy(double deltaSeconds) noexcept;

    /**
     * @brief Jump to the first key strictly after the current time (1 ms tolerance). Keys need
     * not be sorted; keys outside [start, end] are ignored unless Unbounded. In Loop mode stepping
     * past the last key wraps to the first. Returns false when there is no key to go to.
     */
    bool stepToNextKey(std::span<const double> keyTimes) noexcept;
    /** @brief Mirror of stepToNextKey. */
    bool stepToPreviousKey(std::span<const double> keyTimes) noexcept;

    /**
     * @brief Advance data time by `rate * wallDeltaSeconds` and apply the range behaviour.
     *
     * If `nextStepReady` is false and `waitForData` is on, data time holds (CesiumJS
     * canAnimate = false) and `heldFrames` counts the frame, until `maxWaitSeconds` of wall time
     * have been spent holding in a row (then it advances and counts a wait timeout). Paused
     * clocks, rate 0 and non-finite or non-positive wall deltas leave the time unchanged (not
     * counted as held).
     */
    AdvanceResult advance(double wallDeltaSeconds, bool nextStepReady = true) noexcept;

    /**
     * @brief The data time `advance(wallDeltaSeconds)` would reach if the data were ready,
     * without changing anything: bracket it to ask "is the next step ready?" before advancing.
     */
    double predict(double wallDeltaSeconds) const noexcept;

    /** @brief Frames held waiting for data since creation. */
    std::uint64_t heldFrames() const noexcept { return mHeldTotal; }
    /** @brief Consecutive frames held up to now (0 once time moves again). */
    std::uint32_t heldInARow() const noexcept { return mHeldInARow; }
    /** @brief Times the clock stopped waiting because maxWaitSeconds ran out. */
    std::uint64_t waitTimeouts() const noexcept { return mWaitTimeouts; }
    double maxWaitSeconds() const noexcept { return mMaxWait; }
    void setMaxWaitSeconds(double seconds) noexcept { mMaxWait = seconds; }
    /** @brief Loop wraps since creation. */
    std::uint64_t loops() const noexcept { return mLoops; }
    /**
     * @brief Incremented by every seek, seekBy and key step: discontinuities that make in-flight
     * prefetch requests stale (pass changes on to PrefetchPlanner::notifySeek).
     */
    std::uint64_t seekSerial() const noexcept { return mSeekSerial; }

private:
    bool canAdvance(double wallDeltaSeconds) const noexcept;
    double wrapIntoLoop(double t) const noexcept;
    double clampToRange(double t) const noexcept;

    double mStart = 0.0;
    double mEnd = 0.0;
    double mTime = 0.0;
    double mRate = 1.0;
    RangeMode mRange = RangeMode::Loop;
    bool mWaitForData = true;
    bool mPaused = false;
    std::uint64_t mHeldTotal = 0;
    std::uint32_t mHeldInARow = 0;
    double mMaxWait = 5.0;
    double mHeldWallSeconds = 0.0;
    std::uint64_t mWaitTimeouts = 0;
    std::uint64_t mLoops = 0;
    std::uint64_t mSeekSerial = 0;
};

/**
 * @brief Deterministic offline timeline for `render --from T0 --to T1 --fps N`: frame `index`
 * shows data time `t0 + index * |rate| / fps` moving from t0 towards t1 (backwards if t1 < t0),
 * i.e. the video plays `|rate|` data seconds per second of output. Computed by multiplication,
 * never by accumulation, so frame k is bit-identical however a render is split. Results are
 * clamped to t1; a span that is a whole number of steps ends exactly on t1. Non-finite inputs,
 * fps <= 0, rate == 0 or a negative index give t0.
 */
double timeForFrame(double t0, double t1, double fps, std::int64_t index,
                    double rate = 1.0) noexcept;

/** @brief Number of frames `timeForFrame` produces for [t0, t1] (both ends included): >= 1. */
std::int64_t frameCount(double t0, double t1, double fps, double rate = 1.0) noexcept;

/** @brief "loop" / "clamp" / "unbounded" (case-sensitive, as in the scenario schema). */
std::optional<RangeMode> parseRangeMode(std::string_view text) noexcept;
const char* toString(RangeMode mode) noexcept;

}  // namespace kiosk::anim
