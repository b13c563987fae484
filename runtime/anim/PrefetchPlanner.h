#pragma once

#include "runtime/anim/FrameBracket.h"
#include "runtime/anim/ScenarioClock.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace kiosk::anim {

/** @brief Everything the planner needs to know about playback this frame. */
struct PrefetchInput {
    double playhead = 0.0;  ///< current data time (epoch seconds)
    double rate = 1.0;      ///< data seconds per wall second (0 or paused: plan around t)
    RangeMode range = RangeMode::Clamp;
    double rangeStart = 0.0;             ///< clock start / loop start
    double rangeEnd = 0.0;               ///< clock end / loop end
    std::span<const double> frameTimes;  ///< sequence frame times, strictly increasing
    Interpolation mode = Interpolation::Data;
    double meanLoadSeconds = 0.0;     ///< measured mean wall time to make one frame resident
    std::uint64_t bytesPerFrame = 0;  ///< estimated bytes one frame costs for the current view
    std::uint64_t byteBudget = 0;     ///< bytes the cache can give the sequence (0 = no limit)
    int margin = 2;                   ///< extra frames beyond the computed depth
    int maxDepth = 256;               ///< hard cap on the list length
};

/** @brief One frame to prefetch. */
struct PrefetchItem {
    std::size_t frame = 0;
    /** @brief Wall seconds until the playhead needs this frame (0 for the current pair). */
    double deadlineSeconds = 0.0;
};

/** @brief Ordered prefetch request list (most urgent first), rebuilt every frame. */
struct PrefetchPlan {
    std::vector<PrefetchItem> items;
    std::uint64_t generation = 0;  ///< tag requests with it; drop those of older generations
    int depth = 0;                 ///< frames ahead wanted by the deadline rule (before caps)
    bool budgetLimited = false;    ///< the byte budget cut the list short
    bool wrapped = false;          ///< the list continues at the loop start
    /**
     * @brief False when frames are needed faster than they load (|rate| / interval >
     * 1 / meanLoadSeconds): no depth keeps up and the clock will have to wait.
     */
    bool sustainable = true;
};

/**
 * @brief Deadline-aware prefetch for a time sequence.
 *
 * Order: the frames of the current bracket, then frames ahead of the playhead in the playback
 * direction, wrapping to the loop start before the loop end in Loop mode (so a loop restart never
 * waits). Depth = max(ceil(meanLoad * |rate| / mean frame interval), frames whose deadline falls
 * within one mean load time) + margin, capped by byteBudget / bytesPerFrame, maxDepth and the
 * number of distinct frames. The current pair is always listed, even over budget.
 *
 * Generations: `notifySeek` (call it when ScenarioClock::seekSerial changes, i.e. on scrubbing)
 * bumps the generation; the loader drops queued requests of older generations.
 * Thread: render thread; `plan` reuses the vector's capacity (no allocation when warm).
 */
class PrefetchPlanner {
public:
    /** @brief Build this frame's plan into `out` (cleared first). */
    void plan(const PrefetchInput& in, PrefetchPlan& out) const;
    PrefetchPlan plan(const PrefetchInput& in) const {
        PrefetchPlan p;
        plan(in, p);
        return p;
    }

    void notifySeek() noexcept { ++mGeneration; }
    /** @brief Bump the generation iff `clockSeekSerial` differs from the last one seen. */
    bool syncSeekSerial(std::uint64_t clockSeekSerial) noexcept;
    std::uint64_t generation() const noexcept { return mGeneration; }

private:
    std::uint64_t mGeneration = 0;
    std::uint64_t mLastSeekSerial = 0;
};

/**
 * @brief Running mean of frame load times (exponential, so it follows a changing view or disk)
 * feeding PrefetchInput::meanLoadSeconds. Ignores non-finite or negative samples.
 */
class LoadTimeEstimator {
public:
    explicit LoadTimeEstimator(double initialSeconds = 0.05, double weight = 0.2) noexcept
        : mMean(initialSeconds), mWeight(weight) {}
    void record(double seconds) noexcept;
    double mean() const noexcept { return mMean; }
    std::uint64_t samples() const noexcept { return mSamples; }

private:
    double mMean;
    double mWeight;
    std::uint64_t mSamples = 0;
};

}  // namespace kiosk::anim
