#pragma once

#include "runtime/service/Metrics.h"

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

// What the kiosk looks like from outside: the frame loop publishes a ServiceSnapshot after each
// frame (a short copy under a mutex); the HTTP thread copies it out and formats /metrics and
// /health from its copy. The render thread never waits on a scrape: the only shared step is a
// copy of plain data.
namespace kiosk::service {

struct LayerGauge {
    std::string id;
    std::string state;  ///< "ready", "degraded", "failed"
    std::string message;
};

/** @brief Bytes held by each cache, by kind (`kind` label of geokiosk_cache_bytes). */
struct CacheBytes {
    std::uint64_t cpuTiles = 0;
    std::uint64_t gpuTextures = 0;
    std::uint64_t gpuMeshes = 0;
    std::uint64_t sqlitePageCache = 0;
    std::uint64_t luts = 0;       ///< transfer-function LUT textures
    std::uint64_t mappings = 0;   ///< projective-mapping arrays
    std::uint64_t fontAtlas = 0;  ///< overlay font atlas
};

/** @brief The budget of each cache (`kind` label of geokiosk_cache_budget_bytes). */
struct CacheBudgetBytes {
    std::uint64_t cpuTiles = 0;
    std::uint64_t gpu = 0;              ///< GPU textures and meshes together
    std::uint64_t sqlitePageCache = 0;  ///< per connection times the connections open
    std::uint64_t luts = 0;
    std::uint64_t mappings = 0;
    std::uint64_t fontAtlas = 0;
    int storeConnections = 0;
};

/** @brief Plain data describing the running kiosk after its latest frame. */
struct ServiceSnapshot {
    double startedAt = 0;     ///< monotonic seconds when the process started serving
    double lastFrameAt = -1;  ///< monotonic seconds of the last completed frame (-1: none yet)
    std::uint64_t frames = 0;
    FrameHistogram frameMs;
    std::uint64_t heldFrames = 0;             ///< frames a sequence held an older step
    std::uint64_t sequenceMissingFrames = 0;  ///< frames drawn with sequence tiles missing
    CacheBytes cache;
    CacheBudgetBytes budgets;
    std::uint32_t loaderQueue = 0;
    std::vector<LayerGauge> layers;
    std::uint64_t reloads = 0;
    std::uint64_t reloadFailures = 0;
    int playlistIndex = -1;  ///< -1: not playing a playlist
    int playlistLength = 0;
    std::uint64_t playlistSkipped = 0;
    std::string scenario;  ///< file on screen
    double dataTime = 0;   ///< data time drawn (epoch seconds)
    double fps = 0;        ///< over the last second
    bool paused = false;
    bool storeDegraded = false;
    std::uint64_t storeSwaps = 0;  ///< stores replaced on disk and taken over
    std::vector<std::pair<std::string, std::uint64_t>> storeFiles;  ///< path, inode on screen
    std::vector<std::string> warnings;  ///< e.g. skipped playlist entries (shown by /health)
    /** @brief Why the loop keeps the last frame on purpose (empty: it does not), e.g. a wall
     * follower whose leader went silent; /health names it instead of a bare stall. */
    std::string holding;
};

/** @brief The mailbox between the frame loop (writer) and the HTTP thread (reader). */
class SnapshotBox {
public:
    void publish(const ServiceSnapshot& s) {
        std::lock_guard lock(mMutex);
        mSnap = s;  // copy-assign reuses the strings' and vectors' storage: no steady allocation
    }
    ServiceSnapshot read() const {
        std::lock_guard lock(mMutex);
        return mSnap;
    }

private:
    mutable std::mutex mMutex;
    ServiceSnapshot mSnap;
};

/** @brief /health verdict: 200 with a JSON body while frames progress, 503 with the reason. */
struct HealthVerdict {
    int status = 200;
    std::string body;  ///< JSON object
};

/**
 * @brief Judge health at monotonic time `now`: frames must have completed within
 * `stallSeconds`. Before the first frame the reason is "no frame yet".
 */
HealthVerdict evaluateHealth(const ServiceSnapshot& s, double now, double stallSeconds);

/** @brief Process figures read by the HTTP thread (not the render thread). */
struct ProcessFigures {
    std::uint64_t rssBytes = 0;
    std::uint64_t heapBytes = 0;  ///< malloc'd and still in use (all arenas)
    double uptimeSeconds = 0;
};
/** @brief Resident set size from /proc/self/statm (0 if unreadable). */
std::uint64_t readRssBytes();
/**
 * @brief Bytes the C heap hands out and has not been given back (glibc mallinfo2, all arenas):
 * RSS growth with a flat heap is fragmentation or mappings, a growing heap is a leak.
 */
std::uint64_t readHeapInUseBytes();

/** @brief The /metrics text for a snapshot. */
std::string renderMetrics(const ServiceSnapshot& s, const ProcessFigures& process);

}  // namespace kiosk::service
