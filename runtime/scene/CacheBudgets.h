#pragma once

#include <cstddef>
#include <cstdint>

namespace kiosk::scene {

/**
 * @brief Default residency budgets (docs/performance.md). A scenario that leaves
 * `terrain.cacheBytes` / `terrain.gpuBytes` unset gets a cache sized to the working set of the
 * view: what the tiles of the current view and the sequences' prefetched frames occupy, times
 * kWorkingSetMargin, never below the floors. Header-only so `info` (which opens no scene) can
 * print the same figures.
 */
struct CacheDefaults {
    /** @brief Headroom over the measured working set: the budget grows whenever the view
     * presses against it (a refused insert raises the high-water mark next frame), and what a
     * turning camera comes back to stays resident. */
    static constexpr double kWorkingSetMargin = 1.5;
    static constexpr std::size_t kFloorCpuBytes = std::size_t(16) << 20;
    static constexpr std::size_t kFloorGpuBytes = std::size_t(32) << 20;
    /** @brief Per-frame GPU upload budget (bytes and milliseconds of the render thread). */
    static constexpr std::size_t kUploadBytesPerFrame = std::size_t(8) << 20;
    static constexpr double kUploadMsPerFrame = 6.0;
};

/** @brief Working-set sizing: the budget for a measured working set plus what is planned ahead. */
constexpr std::size_t workingSetBudget(std::size_t viewBytes, std::uint64_t aheadBytes,
                                       std::size_t floorBytes) {
    const double want = CacheDefaults::kWorkingSetMargin * (double(viewBytes) + double(aheadBytes));
    return want > double(floorBytes) ? std::size_t(want) : floorBytes;
}

}  // namespace kiosk::scene
