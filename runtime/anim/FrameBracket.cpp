#include "runtime/anim/FrameBracket.h"

#include <algorithm>
#include <cmath>

namespace kiosk::anim {

std::optional<Interpolation> parseInterpolation(std::string_view text) noexcept {
    if (text == "data") return Interpolation::Data;
    if (text == "none") return Interpolation::None;
    if (text == "switch" || text == "categorical") return Interpolation::Categorical;
    if (text == "arrival") return Interpolation::Arrival;
    return std::nullopt;
}

const char* toString(Interpolation mode) noexcept {
    switch (mode) {
        case Interpolation::Data:
            return "data";
        case Interpolation::None:
            return "none";
        case Interpolation::Categorical:
            return "switch";
        case Interpolation::Arrival:
            return "arrival";
    }
    return "data";
}

FrameBracket bracketFrames(std::span<const double> times, double t, Interpolation mode) noexcept {
    FrameBracket b;
    if (times.empty() || !std::isfinite(t)) return b;
    b.valid = true;
    const std::size_t last = times.size() - 1;
    if (t < times.front()) {
        b.beforeFirst = true;
        return b;
    }
    if (t >= times[last]) {
        b.i0 = b.i1 = last;
        b.afterLast = t > times[last];
        return b;
    }
    // First frame strictly after t; t >= times[0] and t < times[last] keep it in [1, last].
    const auto it = std::upper_bound(times.begin(), times.end(), t);
    const auto k1 = static_cast<std::size_t>(it - times.begin());
    const std::size_t k0 = k1 - 1;
    b.i0 = k0;
    b.i1 = k0;
    if (mode == Interpolation::None || mode == Interpolation::Categorical || t == times[k0])
        return b;
    const double span = times[k1] - times[k0];
    if (!(span > 0.0)) return b;
    b.i1 = k1;
    b.alpha = std::clamp((t - times[k0]) / span, 0.0, 1.0);
    // Guard against alpha rounding to exactly 1 for t a hair below the next frame.
    if (b.alpha >= 1.0) b.alpha = std::nextafter(1.0, 0.0);
    return b;
}

double alphaWithin(std::span<const double> times, std::size_t i0, std::size_t i1,
                   double t) noexcept {
    if (i0 >= times.size() || i1 >= times.size() || i0 == i1 || !std::isfinite(t)) return 0.0;
    const double span = times[i1] - times[i0];
    if (!(span > 0.0)) return 0.0;
    return std::clamp((t - times[i0]) / span, 0.0, 1.0);
}

float interpolateValue(float v0, float v1, float alpha, Interpolation mode,
                       std::optional<float> nodataAs, float threshold) noexcept {
    float a = std::isfinite(alpha) ? std::clamp(alpha, 0.0f, 1.0f) : 0.0f;
    const bool nd0 = std::isnan(v0);
    const bool nd1 = std::isnan(v1);
    switch (mode) {
        case Interpolation::None:
            return v0;
        case Interpolation::Categorical:
            if (nodataAs) {
                if (nd0) v0 = *nodataAs;
                if (nd1) v1 = *nodataAs;
            }
            return a >= 1.0f ? v1 : v0;
        case Interpolation::Arrival: {
            if (nodataAs) {
                if (nd0) v0 = *nodataAs;
                if (nd1) v1 = *nodataAs;
            }
            // A NaN threshold (unknown arrival) switches at the next frame, like arrivalThreshold.
            const float th = std::isnan(threshold) ? 1.0f : threshold;
            return a >= th ? v1 : v0;
        }
        case Interpolation::Data:
            if (nd0 && nd1) return v0;
            if (nd0 || nd1) {
                if (!nodataAs) return a < 0.5f ? v0 : v1;
                if (nd0) v0 = *nodataAs;
                if (nd1) v1 = *nodataAs;
            }
            // Written exactly as GLSL defines mix() so the shader goldens match bit for bit on
            // IEEE hardware (llvmpipe).
            return v0 * (1.0f - a) + v1 * a;
    }
    return v0;
}

float arrivalThreshold(double arrivalTime, double t0, double t1) noexcept {
    if (std::isnan(arrivalTime)) return 1.0f;
    const double span = t1 - t0;
    if (!(span > 0.0)) return 0.0f;
    return static_cast<float>(std::clamp((arrivalTime - t0) / span, 0.0, 1.0));
}

}  // namespace kiosk::anim
