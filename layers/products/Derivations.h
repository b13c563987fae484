#pragma once

#include "runtime/loader/Derivation.h"

#include <array>
#include <optional>
#include <string>

// The loader-side half of the derived products (docs/products.md): each turns the stored frames
// of a sequence into the state the product's shader combines with the value on screen. Times are
// in the product's time unit since its origin (the clock start), so a 16-bit float keeps a
// relative precision of 1/2048 of the value (under 2 min at 48 h).
namespace kiosk::layers::products {

/** @brief Time axis of a time-valued product: value = (epoch seconds - origin) / unit. */
struct TimeAxis {
    double origin = 0;   ///< epoch seconds (the scenario clock's start)
    double unit = 3600;  ///< seconds per product unit (h: 3600, min: 60, s: 1)
    float at(double epochSeconds) const { return float((epochSeconds - origin) / unit); }
};

/**
 * @brief What the cumulative products share: a state of (value, frame k's value) per post and
 * the tile's texels, per post (r, g, b, a) = (value x valid, v_k, v_k+1, valid) where valid says
 * the state has a value and v are the frames on screen (nodata: the layer's nodataAs, else
 * kNoValue, below any threshold and any maximum). The shader reads all four from one texel.
 */
class Cumulative : public loader::Derivation {
public:
    /** @brief A frame value standing for nodata on screen (half-float range, far below data). */
    static constexpr float kNoValue = -60000.0f;
    explicit Cumulative(std::optional<double> nodataAs) : mNodataAs(nodataAs) {}
    int stateFloats() const override { return 2; }  // value, frame k's value
    void start(std::span<float> state) const override;
    void finish(std::span<const float> state, std::span<const float> next,
                std::span<float> out) const override;

protected:
    std::optional<double> mNodataAs;
};

/** @brief Maximum so far: max of the valid values of frames 0..k (none where none was valid). */
class MaximumSoFar final : public Cumulative {
public:
    using Cumulative::Cumulative;
    void advance(std::span<float> state, std::span<const float> values, double time,
                 double previousTime) const override;
};

/**
 * @brief Arrival time: the first time the value reaches `threshold`, interpolated linearly
 * between the two frames around the crossing (the value itself is interpolated so on screen);
 * at the first frame, after a nodata frame, or for class data (`stepwise`: burn states are not
 * interpolated), the frame's own time. None: not yet. Nodata counts as below the threshold.
 */
class ArrivalTime final : public Cumulative {
public:
    ArrivalTime(double threshold, TimeAxis axis, std::optional<double> nodataAs, bool stepwise)
        : Cumulative(nodataAs), mThreshold(float(threshold)), mAxis(axis), mStepwise(stepwise) {}
    void advance(std::span<float> state, std::span<const float> values, double time,
                 double previousTime) const override;

private:
    float mThreshold;
    TimeAxis mAxis;
    bool mStepwise;
};

/**
 * @brief Duration above `threshold` up to frame k: the time the linearly interpolated value
 * spends at or above it (an interval with a nodata end adds nothing); for class data
 * (`stepwise`) a frame's class holds until the next frame. None until the pixel has had a
 * valid value.
 */
class DurationAbove final : public Cumulative {
public:
    DurationAbove(double threshold, double unitSeconds, std::optional<double> nodataAs,
                  bool stepwise)
        : Cumulative(nodataAs),
          mThreshold(float(threshold)),
          mUnit(unitSeconds),
          mStepwise(stepwise) {}
    void advance(std::span<float> state, std::span<const float> values, double time,
                 double previousTime) const override;

private:
    float mThreshold;
    double mUnit;
    bool mStepwise;
};

/**
 * @brief Flood hazard class H1..H6 of Australian Rainfall and Runoff 2019 (Book 6 Chapter 7,
 * Table 6.7.4, after Smith, Davey and Cox 2014): the first class whose depth, velocity and
 * depth x velocity limits all hold. Class k (1..5) has limits kDepth[k-1] m, kVelocity[k-1] m/s,
 * kProduct[k-1] m2/s; H6 has none.
 */
struct HazardCurves {
    static constexpr std::array<double, 5> kDepth{0.3, 0.5, 1.2, 2.0, 4.0};
    static constexpr std::array<double, 5> kVelocity{2.0, 2.0, 2.0, 2.0, 4.0};
    static constexpr std::array<double, 5> kProduct{0.3, 0.6, 0.6, 1.0, 4.0};
    /** @brief Class 1..6 for a wet pixel (depth > 0), 0 when dry. */
    static int classOf(double depth, double velocity);
    /** @brief Depth-only fallback (no velocity in the data): the depth limits alone. */
    static int classOfDepth(double depth);
};

/**
 * @brief Per frame: hazard class of the depth frame and the velocity frame of `velocity`
 * (same store, same frames), or of the depth alone when `velocity` is empty. NaN where dry or
 * nodata.
 */
class HazardClass final : public loader::Derivation {
public:
    explicit HazardClass(std::string velocity) : mVelocity(std::move(velocity)) {}
    const std::string& companion() const override { return mVelocity; }
    void combine(std::span<float> values, std::span<const float> other) const override;

private:
    std::string mVelocity;
};

}  // namespace kiosk::layers::products
