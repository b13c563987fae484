#pragma once

#include "runtime/core/Result.h"
#include "runtime/math/Camera.h"

#include <array>
#include <optional>
#include <string_view>
#include <vector>

namespace kiosk::anim {

/** @brief A viewpoint pinned to a data time (epoch seconds). */
struct CameraKey {
    double time = 0.0;
    math::Viewpoint view;
};

/** @brief How a camera path moves between keys (scenario `interpolation`). */
enum class PathInterpolation {
    Smooth,  ///< monotone cubic Hermite, C1, eased ends (the default)
    Linear,  ///< piecewise linear per channel (heading shortest arc, range geometric)
    Step     ///< jump to each key at its time (cuts)
};
/** @brief "smooth" / "linear" / "step". */
std::optional<PathInterpolation> parsePathInterpolation(std::string_view text) noexcept;

/**
 * @brief A camera path keyed to the scenario clock.
 *
 * Each channel (target x, y, z; heading; pitch; log range) is a monotone cubic Hermite spline
 * (Fritsch-Carlson / PCHIP tangents) in *time*, so the path passes through every key, is C1 in
 * time across keys with uneven spacing, and never overshoots between keys (no range dipping below
 * both neighbours, no target swinging past a key). Tangents are zero at the first and last key:
 * the path eases in and out. Heading takes the shorter arc between consecutive keys (350 -> 10
 * goes through 0, not 180); range is interpolated in log space so zooms have constant relative
 * speed; pitch is clamped to [-90, 90]. Before the first key the first view holds, after the last
 * key the last one.
 *
 * `PathInterpolation::Linear` and `Step` replace the Hermite segments by straight segments (same
 * heading and range rules) or by cuts at the key times.
 *
 * Thread: immutable after `create`; const methods may be called from any thread.
 */
class CameraPath {
public:
    CameraPath() = default;

    /**
     * @brief Validate keys and precompute tangents. Keys must be in strictly increasing time.
     * Errors (`where` is the JSON pointer of the path, keys are `where/keys/i/...`):
     * ANIM_PATH_EMPTY, ANIM_PATH_NOT_FINITE, ANIM_PATH_KEYS_UNSORTED, ANIM_PATH_RANGE_INVALID
     * (range <= 0), ANIM_PATH_PITCH_INVALID (outside [-90, 90]).
     */
    static Result<CameraPath> create(std::vector<CameraKey> keys, std::string_view file = {},
                                     std::string_view where = {},
                                     PathInterpolation mode = PathInterpolation::Smooth);

    bool empty() const noexcept { return mKeys.empty(); }
    PathInterpolation interpolation() const noexcept { return mMode; }
    const std::vector<CameraKey>& keys() const noexcept { return mKeys; }
    double startTime() const noexcept { return mKeys.empty() ? 0.0 : mKeys.front().time; }
    double endTime() const noexcept { return mKeys.empty() ? 0.0 : mKeys.back().time; }

    /** @brief The view at data time t (default Viewpoint for an empty path or NaN t). */
    math::Viewpoint sample(double t) const noexcept;
    /** @brief The view `dt` data seconds ahead of t: what the loader should prefetch for. */
    math::Viewpoint sampleAhead(double t, double dt) const noexcept { return sample(t + dt); }
    /**
     * @brief `count` views evenly spaced over (t, t + dt] into `out` (cleared; capacity reused),
     * for prefetching tiles along the coming stretch of the path.
     */
    void sampleAlong(double t, double dt, int count, std::vector<math::Viewpoint>& out) const;

private:
    enum Channel { kX, kY, kZ, kHeading, kPitch, kLogRange, kChannels };
    std::vector<CameraKey> mKeys;
    PathInterpolation mMode = PathInterpolation::Smooth;
    std::vector<double> mTimes;
    std::array<std::vector<double>, kChannels> mValues;
    std::array<std::vector<double>, kChannels> mTangents;
};

/**
 * @brief A smooth transition to a named viewpoint over `duration` seconds (wall or data time,
 * whichever clock the caller passes to `sample`).
 *
 * Progress is eased with smootherstep (zero velocity and acceleration at both ends). Target and
 * pitch move linearly in eased progress, heading along the shorter arc, range in log space; when
 * the targets are far apart compared with the ranges the range rises along an arc in the middle
 * (peak about 0.75 x the target distance) so the viewer sees where the camera is going.
 * Thread: value type, no shared state.
 */
class FlyTo {
public:
    FlyTo() = default;
    /** @brief Non-finite or non-positive durations make the transition instantaneous. */
    FlyTo(const math::Viewpoint& from, const math::Viewpoint& to, double startTime,
          double durationSeconds) noexcept;

    math::Viewpoint sample(double now) const noexcept;
    /** @brief True once `now` reached the end (always true for a default FlyTo). */
    bool finished(double now) const noexcept { return !(now < mStart + mDuration); }
    double endTime() const noexcept { return mStart + mDuration; }
    const math::Viewpoint& destination() const noexcept { return mTo; }

private:
    math::Viewpoint mFrom;
    math::Viewpoint mTo;
    double mStart = 0.0;
    double mDuration = 0.0;
    double mArcLog = 0.0;  ///< extra log-range at mid-flight
};

/** @brief Signed heading difference b - a in degrees, in (-180, 180]. */
double shortestHeadingDelta(double aDeg, double bDeg) noexcept;
/** @brief Heading normalised into [0, 360). */
double normalizeHeading(double deg) noexcept;
/** @brief 6s^5 - 15s^4 + 10s^3 on s clamped to [0, 1]. */
double smootherstep(double s) noexcept;

}  // namespace kiosk::anim
