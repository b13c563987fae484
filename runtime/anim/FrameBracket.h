#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

namespace kiosk::anim {

/**
 * @brief How a sequence layer turns two frames into the value shown at time t (scenario
 * `interpolate`). See docs/animation.md for the shader side.
 */
enum class Interpolation {
    Data,         ///< "data": mix the data values, then apply the transfer function
    None,         ///< "none": the raw step, frame at or before t (audit view)
    Categorical,  ///< "switch": class data, switch to the next frame without blending
    Arrival       ///< "arrival": class data, a pixel switches when alpha passes its threshold
};

std::optional<Interpolation> parseInterpolation(std::string_view text) noexcept;
const char* toString(Interpolation mode) noexcept;

/** @brief The two frames bracketing a time and the blend factor between them. */
struct FrameBracket {
    std::size_t i0 = 0;  ///< frame at or before t (0 before the first frame)
    std::size_t i1 = 0;  ///< frame after t; equals i0 when only one frame is needed
    double alpha = 0.0;  ///< in [0, 1): weight of i1; 0 whenever i0 == i1
    bool valid = false;  ///< false for an empty sequence or a non-finite t
    bool beforeFirst = false;
    bool afterLast = false;

    bool operator==(const FrameBracket&) const = default;
};

/**
 * @brief Bracket `t` in `frameTimes` (strictly increasing, irregular spacing allowed).
 *
 * - Data / Arrival: t in [t_k, t_k+1) gives (k, k+1, (t - t_k) / (t_k+1 - t_k)); exactly on a
 *   frame gives (k, k, 0) so a still frame needs only one frame resident.
 * - None / Categorical: (k, k, 0) with k the frame at or before t.
 * - Outside the range the result clamps to the first / last frame (i0 == i1, alpha 0) and sets
 *   beforeFirst / afterLast.
 * Thread: pure function. Unsorted input gives an unspecified (but in-range) bracket.
 */
FrameBracket bracketFrames(std::span<const double> frameTimes, double t,
                           Interpolation mode) noexcept;

/**
 * @brief Blend factor of `t` within frames (i0, i1), clamped to [0, 1]. Used to show a held pair
 * at the time nearest to t (see VisiblePair). 0 when i0 == i1 or indices are out of range.
 */
double alphaWithin(std::span<const double> frameTimes, std::size_t i0, std::size_t i1,
                   double t) noexcept;

/**
 * @brief CPU reference of the sequence shader's value interpolation (the golden tests compare
 * rendered pixels with LUT(interpolateValue(...))). NaN is nodata (io::RasterTile convention).
 *
 * - Data: GLSL `mix(v0, v1, alpha)` = v0 * (1 - alpha) + v1 * alpha. A nodata side takes
 *   `nodataAs` (e.g. depth 0) so wet/dry fronts advance smoothly; with both sides nodata the
 *   result stays nodata; without `nodataAs` a one-sided nodata pixel switches at alpha 0.5.
 * - None: v0 (raw, nodata stays nodata).
 * - Categorical: v0 until alpha reaches 1, then v1; never a blend.
 * - Arrival: v1 once alpha >= `arrivalThreshold` (the pixel's fractional arrival time within the
 *   interval, in [0, 1]), else v0; never a blend. Nodata sides take `nodataAs` when given.
 * Non-finite alpha is treated as 0; alpha is clamped to [0, 1].
 */
float interpolateValue(float v0, float v1, float alpha, Interpolation mode,
                       std::optional<float> nodataAs, float arrivalThreshold = 0.5f) noexcept;

/**
 * @brief A pixel's arrival threshold from an arrival-time raster (fire models write one): the
 * fraction of the interval [t0, t1] at which `arrivalTime` falls, clamped to [0, 1]. Nodata or
 * unknown arrival (NaN) gives 1 (switch at the next frame); a degenerate interval gives 0.
 */
float arrivalThreshold(double arrivalTime, double t0, double t1) noexcept;

}  // namespace kiosk::anim
