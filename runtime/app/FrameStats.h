#pragma once

#include "runtime/core/Diagnostics.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace kiosk::app {

/** @brief One frame's record (docs/cli.md `--stats`). */
struct FrameRecord {
    double frameMs = 0;
    std::uint32_t tilesDrawn = 0;
    std::uint64_t triangles = 0;
    std::uint32_t tilesFromAncestor = 0;
    std::uint32_t tilesOccluded = 0;  ///< hidden behind nearer terrain, not drawn
    std::uint32_t sequenceTilesMissing = 0;
    std::uint64_t residentBytes = 0;
    double dataTime = 0;  ///< scenario time shown (epoch seconds)
    bool holdingSequence = false;   ///< a sequence showed an older complete pair (held)
    std::uint32_t heldFrames = 0;   ///< consecutive held frames, this one included
    std::int32_t prefetchDepth = 0; ///< frames ahead the prefetch planner wanted
    std::uint32_t prefetchHits = 0; ///< frames shown this frame that were prefetched in time
    std::uint32_t mappingsActive = 0;         ///< projective mappings evaluated
    std::uint32_t mappingsCulledFrustum = 0;  ///< outside the view frustum
    std::uint32_t mappingsCulledSize = 0;     ///< screen-space size below the threshold
    // Main-thread time per phase of drawFrame() (ms; the rasterizer's share lands in whatever
    // waits for it: glFinish / swap). Feeds the benchmarks' per-phase figures.
    double updateMs = 0;   ///< select + drain completions + uploads
    double uploadMs = 0;   ///< of updateMs: GPU uploads of arrived tiles
    std::uint32_t uploads = 0;
    double drawMs = 0;     ///< terrain draw submission (vertex work, binning, shader variants)
    double overlayMs = 0;  ///< overlays
    // What the frame was drawn with: the scenario's tau, or the frame-rate governor's (play).
    double tauGeom = 0;
    double tauTex = 0;
    double renderScale = 1;  ///< fraction of the output size the terrain was rendered at
};

/** @brief Percentile by linear interpolation between closest ranks (p in [0,100]). */
double percentile(std::vector<double> values, double p);

/**
 * @brief Collects frame records; preallocated so recording never allocates in the frame loop
 * until the reserve is exhausted.
 */
class FrameStats {
public:
    explicit FrameStats(std::size_t reserve = 4096) { mFrames.reserve(reserve); }
    /**
     * @brief Keep only the newest `window` records (`play` may run for weeks): the oldest is
     * overwritten once the window is full, so memory stays bounded and add() never allocates.
     * summary.frames_dropped counts the overwritten ones.
     */
    void keepNewest(std::size_t window) {
        mWindow = window;
        mFrames.reserve(window);
    }
    void add(const FrameRecord& r) {
        if (mWindow > 0 && mFrames.size() >= mWindow) {
            mFrames[mNext] = r;
            mNext = (mNext + 1) % mFrames.size();
            ++mDropped;
            return;
        }
        mFrames.push_back(r);
    }
    /** @brief Records in storage order (chronological unless the window wrapped). */
    const std::vector<FrameRecord>& frames() const noexcept { return mFrames; }
    /** @brief Named byte/time budgets in effect (cache, uploads, prefetch), as `budgets` in JSON.
     */
    void setBudgets(std::vector<std::pair<std::string, double>> budgets) {
        mBudgets = std::move(budgets);
    }
    /** @brief JSON object: per-frame arrays, summary {median,p95,p99} of frame_ms, budgets. */
    std::string toJson() const;
    bool write(const std::filesystem::path& path, Diagnostics& diags) const;

private:
    std::vector<FrameRecord> mFrames;
    std::size_t mWindow = 0, mNext = 0;
    std::uint64_t mDropped = 0;
    std::vector<std::pair<std::string, double>> mBudgets;
};

}  // namespace kiosk::app
