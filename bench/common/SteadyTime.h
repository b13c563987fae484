#pragma once
// One time base for benchmark processes that compare timestamps: steady_clock is system-wide on
// Linux (CLOCK_MONOTONIC), so a leader and its follower processes can subtract each other's
// readings (bench-wall's skew).
#include <chrono>

namespace kiosk::bench {

/** @brief Microseconds on the machine's monotonic clock. */
inline double nowUs() {
    return std::chrono::duration<double, std::micro>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace kiosk::bench
