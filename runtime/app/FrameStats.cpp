#include "runtime/app/FrameStats.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace kiosk::app {

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double rank = std::clamp(p, 0.0, 100.0) / 100.0 * double(v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(rank));
    const auto hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (v[hi] - v[lo]) * (rank - double(lo));
}

std::string FrameStats::toJson() const {
    nlohmann::json j;
    std::vector<double> ms;
    std::uint64_t missingFrames = 0, heldTotal = 0, hitsTotal = 0;
    auto& frames = j["frames"];
    frames = nlohmann::json::object();
    for (std::size_t k = 0; k < mFrames.size(); ++k) {
        const FrameRecord& f = mFrames[(mNext + k) % mFrames.size()];  // oldest first
        ms.push_back(f.frameMs);
        frames["frame_ms"].push_back(f.frameMs);
        frames["tiles_drawn"].push_back(f.tilesDrawn);
        frames["triangles"].push_back(f.triangles);
        frames["tiles_from_ancestor"].push_back(f.tilesFromAncestor);
        frames["tiles_occluded"].push_back(f.tilesOccluded);
        frames["sequence_tiles_missing"].push_back(f.sequenceTilesMissing);
        frames["resident_bytes"].push_back(f.residentBytes);
        frames["data_time"].push_back(f.dataTime);
        frames["held_frames"].push_back(f.heldFrames);
        frames["prefetch_depth"].push_back(f.prefetchDepth);
        frames["prefetch_hits"].push_back(f.prefetchHits);
        missingFrames += f.sequenceTilesMissing > 0 ? 1u : 0u;
        heldTotal += f.holdingSequence ? 1u : 0u;
        hitsTotal += f.prefetchHits;
        frames["mappings_active"].push_back(f.mappingsActive);
        frames["mappings_culled_frustum"].push_back(f.mappingsCulledFrustum);
        frames["mappings_culled_size"].push_back(f.mappingsCulledSize);
        frames["tau_geom"].push_back(f.tauGeom);
        frames["tau_tex"].push_back(f.tauTex);
        frames["render_scale"].push_back(f.renderScale);
    }
    j["summary"] = {{"frames", mFrames.size()},
                    {"frame_ms",
                     {{"median", percentile(ms, 50)},
                      {"p95", percentile(ms, 95)},
                      {"p99", percentile(ms, 99)}}},
                    {"sequence_missing_frames", missingFrames},
                    {"held_frames", heldTotal},
                    {"prefetch_hits", hitsTotal},
                    {"frames_dropped", mDropped}};
    auto& budgets = j["budgets"];
    budgets = nlohmann::json::object();
    for (const auto& [name, value] : mBudgets) budgets[name] = value;
    return j.dump(1);
}

bool FrameStats::write(const std::filesystem::path& path, Diagnostics& diags) const {
    const auto tmp = path.string() + ".tmp";
    {
        std::ofstream f(tmp);
        if (!(f << toJson() << '\n')) {
            diags.error("OUTPUT_WRITE", path.string(), "", "cannot write statistics");
            return false;
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        diags.error("OUTPUT_WRITE", path.string(), "", "cannot write statistics: " + ec.message());
        return false;
    }
    return true;
}

}  // namespace kiosk::app
