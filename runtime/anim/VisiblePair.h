#pragma once

#include "runtime/anim/FrameBracket.h"

#include <cstddef>
#include <cstdint>
#include <span>

namespace kiosk::anim {

/** @brief What a sequence layer draws this frame. */
struct DisplayPair {
    bool hasPair = false;  ///< false until a first pair was complete; draw nothing (or fallback)
    std::size_t i0 = 0;
    std::size_t i1 = 0;
    double alpha = 0.0;    ///< blend within (i0, i1) for the current time, clamped to [0, 1]
    bool holding = false;  ///< the wanted pair is not complete; an older pair (or none) is shown
    std::uint32_t heldFrames = 0;  ///< consecutive frames holding, this one included
};

/**
 * @brief Atomic time steps: a new frame pair becomes visible only when every tile the current
 * view needs is resident for both of its frames; until then the previous pair stays (never a mix
 * of times on screen).
 *
 * Each frame the caller passes the wanted bracket for the current time and a predicate
 * `complete(frameIndex) -> bool` ("all tiles this view needs are resident for that frame"). The
 * held pair is shown with alpha recomputed for the current time and clamped, so if the clock
 * runs on while waiting, the screen shows the held pair's frame nearest to now (e.g. the
 * shared frame k of (k-1, k) while (k, k+1) loads) rather than freezing at an old blend.
 *
 * The cache must keep the frames of `displayed()` resident (pin them) or the guarantee is void.
 * Thread: render thread; not thread-safe. No allocation.
 */
class VisiblePair {
public:
    /**
     * @brief Decide the pair to draw. `frameTimes` are the sequence's times (for alpha), `t` the
     * current data time. An invalid bracket (empty sequence) keeps the current display.
     */
    template <class CompletePredicate>
    DisplayPair update(const FrameBracket& wanted, std::span<const double> frameTimes, double t,
                       CompletePredicate&& complete) {
        const bool ok = wanted.valid && wanted.i0 < frameTimes.size() &&
                        wanted.i1 < frameTimes.size() && complete(wanted.i0) &&
                        (wanted.i1 == wanted.i0 || complete(wanted.i1));
        return commit(wanted, ok, frameTimes, t);
    }

    /** @brief The pair on screen (valid when `hasPair`). */
    const DisplayPair& displayed() const noexcept { return mShown; }
    /** @brief Frames held (wanted pair incomplete) since creation or reset. */
    std::uint64_t totalHeldFrames() const noexcept { return mTotalHeld; }
    /** @brief Number of pair changes since creation or reset. */
    std::uint64_t switches() const noexcept { return mSwitches; }
    /** @brief Forget the shown pair (sequence replaced, scenario reloaded). */
    void reset() noexcept { *this = VisiblePair(); }

private:
    DisplayPair commit(const FrameBracket& wanted, bool wantedComplete,
                       std::span<const double> frameTimes, double t) noexcept;

    DisplayPair mShown;
    std::uint64_t mTotalHeld = 0;
    std::uint64_t mSwitches = 0;
};

}  // namespace kiosk::anim
