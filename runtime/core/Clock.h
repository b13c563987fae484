#pragma once

#include <chrono>

namespace kiosk {

/**
 * @brief Source of wall time for the frame loop. Seconds as double since an arbitrary epoch.
 * RealClock for play, FakeClock for render/tests (deterministic).
 */
class Clock {
public:
    virtual ~Clock() = default;
    virtual double now() const = 0;
};

class RealClock final : public Clock {
public:
    double now() const override;
};

/** @brief Manually advanced clock; `advance` is the only way time passes. */
class FakeClock final : public Clock {
public:
    explicit FakeClock(double start = 0.0) : mNow(start) {}
    double now() const override { return mNow; }
    void advance(double seconds) { mNow += seconds; }
    void set(double seconds) { mNow = seconds; }

private:
    double mNow;
};

}  // namespace kiosk
