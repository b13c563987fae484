#pragma once

#include <array>
#include <cstddef>

namespace kiosk::app {

/**
 * @brief When each start-up step of a command ended, in seconds since the process was started
 * (exec), so a start-up's phases are numbers (docs/performance.md §5.2). Logged at debug level
 * (GEOKIOSK_LOG=debug): "start-up: display 0.231 s, session 0.305 s, ...". A fixed array: marking
 * never allocates.
 */
class StartupPhases {
public:
    /** @brief Record that step `name` (a string literal) ended now; later marks are dropped. */
    void mark(const char* name) noexcept;
    /** @brief One debug line with every mark under `tag`. */
    void log(const char* tag) const;

    /**
     * @brief Seconds since this process was exec'd: CLOCK_BOOTTIME now minus the start time in
     * /proc/self/stat (clock ticks, 10 ms on Linux); negative when that is unreadable.
     */
    static double sinceProcessStart() noexcept;

private:
    struct Mark {
        const char* name = nullptr;
        double seconds = 0.0;
    };
    std::array<Mark, 12> mMarks{};
    std::size_t mCount = 0;
};

}  // namespace kiosk::app
