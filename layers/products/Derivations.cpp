#include "layers/products/Derivations.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kiosk::layers::products {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace

void Cumulative::start(std::span<float> state) const {
    std::fill(state.begin(), state.end(), kNaN);
}

void Cumulative::finish(std::span<const float> state, std::span<const float> next,
                        std::span<float> out) const {
    auto onScreen = [&](float v) {
        return !std::isnan(v) ? v : mNodataAs ? float(*mNodataAs) : kNoValue;
    };
    const std::size_t n = state.size() / 2;
    for (std::size_t i = 0; i < n; ++i) {
        const float value = state[2 * i], vk = state[2 * i + 1];
        const bool valid = !std::isnan(value);
        float* texel = &out[4 * i];
        texel[0] = valid ? value : 0.0f;
        texel[1] = onScreen(vk);
        texel[2] = next.empty() ? texel[1] : onScreen(next[i]);
        texel[3] = valid ? 1.0f : 0.0f;
    }
}

void MaximumSoFar::advance(std::span<float> state, std::span<const float> values, double,
                           double) const {
    for (std::size_t i = 0; i < values.size(); ++i) {
        const float v = values[i];
        float& maximum = state[2 * i];
        state[2 * i + 1] = v;
        if (std::isnan(v)) continue;
        maximum = std::isnan(maximum) ? v : std::max(maximum, v);
    }
}

void ArrivalTime::advance(std::span<float> state, std::span<const float> values, double time,
                          double previousTime) const {
    const float t1 = mAxis.at(time);
    const float t0 = std::isnan(previousTime) ? t1 : mAxis.at(previousTime);
    for (std::size_t i = 0; i < values.size(); ++i) {
        float& arrival = state[2 * i];
        float& previous = state[2 * i + 1];
        const float v = values[i];
        if (std::isnan(arrival) && !std::isnan(v) && v >= mThreshold) {
            // Crossing inside the interval when the previous frame was valid and below.
            if (!mStepwise && !std::isnan(previous) && previous < mThreshold)
                arrival = t0 + (mThreshold - previous) / (v - previous) * (t1 - t0);
            else
                arrival = t1;
        }
        previous = v;
    }
}

void DurationAbove::advance(std::span<float> state, std::span<const float> values, double time,
                            double previousTime) const {
    const double dt = std::isnan(previousTime) ? 0.0 : (time - previousTime) / mUnit;
    for (std::size_t i = 0; i < values.size(); ++i) {
        float& duration = state[2 * i];
        float& previous = state[2 * i + 1];
        const float v = values[i];
        if (!std::isnan(v) && std::isnan(duration)) duration = 0.0f;
        if (!std::isnan(v) && !std::isnan(previous) && dt > 0.0) {
            // Fraction of the interval the linear value spends at or above the threshold.
            double f = 0.0;
            const bool a = previous >= mThreshold, b = v >= mThreshold;
            if (mStepwise) {
                f = a ? 1.0 : 0.0;
            } else if (a && b) {
                f = 1.0;
            } else if (a != b) {
                const double s = (double(mThreshold) - previous) / (double(v) - previous);
                f = a ? s : 1.0 - s;
            }
            duration = float(double(duration) + f * dt);
        }
        previous = v;
    }
}

int HazardCurves::classOf(double depth, double velocity) {
    if (!(depth > 0.0)) return 0;
    for (std::size_t k = 0; k < kDepth.size(); ++k)
        if (depth <= kDepth[k] && velocity <= kVelocity[k] && depth * velocity <= kProduct[k])
            return int(k) + 1;
    return 6;
}

int HazardCurves::classOfDepth(double depth) {
    if (!(depth > 0.0)) return 0;
    for (std::size_t k = 0; k < kDepth.size(); ++k)
        if (depth <= kDepth[k]) return int(k) + 1;
    return 6;
}

void HazardClass::combine(std::span<float> values, std::span<const float> other) const {
    for (std::size_t i = 0; i < values.size(); ++i) {
        const float d = values[i];
        int c = 0;
        if (!std::isnan(d)) {
            if (mVelocity.empty()) {
                c = HazardCurves::classOfDepth(d);
            } else if (i < other.size() && !std::isnan(other[i])) {
                c = HazardCurves::classOf(d, other[i]);
            }
        }
        values[i] = c > 0 ? float(c) : kNaN;
    }
}

}  // namespace kiosk::layers::products
